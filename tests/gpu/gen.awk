# tests/gpu/gen.awk - evaluation wrappers for the GPU check (tests/gpu/run.sh), on the parser of
# tests/portability/gen.awk (which discovers every public function of every header and knows
# which are GLSL-callable). Load it FIRST, so that its END runs (and exits) before gen.awk's:
#
#   awk -v out=glsl -v targets=pf_smith.h -v includes="pf_core.h pf_smith.h" \
#       -f tests/gpu/gen.awk -f tests/portability/gen.awk include/pf_*.h     > pf_smith.comp
#   awk -v out=c [-v targets="..."] -f tests/gpu/gen.awk -f tests/portability/gen.awk include/pf_*.h > fns.c
#
# Every GLSL-callable public function (not inside #ifndef PF_GLSL) gets one wrapper that reads
# its scalar inputs ("slots") from a buffer, calls it, and writes every scalar leaf of the
# result to its own output, so results are compared element by element:
#   glsl  void pfg_f<k>(uint i): inputs pfg_in.v[i * NIN + s], outputs pfg_out.v[i * NOUT + j];
#         main() switches on the push constant fn over the functions of `targets`.
#   c     static void pfg_c_<name>(const float *in, double *out), and a table PFG_TABLE (name,
#         header, index within the header's shader, NIN, NOUT, slot names, wrapper), compiled
#         three times by vk_run.c's build: float, double (-DPF_DOUBLE) and the emulated driver.
# Slots are named after the parameters they feed, through makers (pf_vec3_make(x, y, z) gives
# "wo.x wo.y wo.z"), so tests/gpu/domains.txt can give each its domain. int parameters read a
# real slot and convert it (the domain table gives them integral values).

# Struct members as written, arrays included (gen.awk marks a struct with an array member as
# one it cannot synthesise; here its members are read again: "type name;" or "type name[N];",
# N a number or a #define'd number).
{
    g_line = $0
    gsub(/\/\*.*\*\//, "", g_line)
    if (g_line ~ /^[ \t]*#[ \t]*define[ \t]+[A-Za-z_][A-Za-z0-9_]*[ \t]+[0-9]+[ \t]*$/) {
        sub(/^[ \t]*#[ \t]*define[ \t]+/, "", g_line); split(g_line, g_t, /[ \t]+/); g_def[g_t[1]] = g_t[2] + 0
    } else if (g_line ~ /PF_STRUCT_BEGIN[ \t]*\(/) {
        g_cur = g_line; sub(/^.*PF_STRUCT_BEGIN[ \t]*\([ \t]*/, "", g_cur); sub(/[ \t]*\).*$/, "", g_cur)
        g_mn[g_cur] = 0
    } else if (g_cur != "" && g_line ~ /PF_STRUCT_END/) {
        g_cur = ""
    } else if (g_cur != "" && g_line ~ /^[ \t]*[A-Za-z_][A-Za-z0-9_]*[ \t]+[A-Za-z_][A-Za-z0-9_]*[ \t]*(\[[ \t]*[A-Za-z0-9_]+[ \t]*\])?[ \t]*;/) {
        sub(/;.*$/, "", g_line); gsub(/[][]/, " ", g_line); g_k = split(g_line, g_t, /[ \t]+/)
        g_j = (g_t[1] == "") ? 2 : 1
        g_mn[g_cur]++
        g_mtype[g_cur, g_mn[g_cur]] = g_t[g_j]; g_mname[g_cur, g_mn[g_cur]] = g_t[g_j + 1]
        g_msize[g_cur, g_mn[g_cur]] = (g_k >= g_j + 2 && g_t[g_j + 2] != "") ? g_t[g_j + 2] : ""
    }
}

# elements of an array member: its size, or 0 when unknown
function g_count(sz) { if (sz ~ /^[0-9]+$/) return sz + 0; return (sz in g_def) ? g_def[sz] : 0 }

function g_in(k) { return (out == "glsl") ? "pfg_in.v[b + " k "u]" : "in[" k "]" }

# expression of type t for parameter path `path` of function f; appends slot names to g_slots
function g_synth(t, path, f, lvl,    mk, i, na, a, e, v, pn) {
    if (lvl > 8) die("type nesting too deep in " f)
    if (t == "pf_real") { g_slots = g_slots " " path; return g_in(g_nin++) }
    if (t == "int") {
        g_slots = g_slots " " path
        return (out == "glsl") ? "int(" g_in(g_nin++) ")" : "(int)" g_in(g_nin++)
    }
    mk = t "_make"
    if ((t in struct_bad) && g_mn[t] > 0) {          # arrays: member by member, element by element
        v = "pfg_a" (++g_nloc)
        g_setup = g_setup "    " t " " v ";\n"
        for (i = 1; i <= g_mn[t]; i++) {
            if (g_msize[t, i] == "") {
                e = g_synth(g_mtype[t, i], path "." g_mname[t, i], f, lvl + 1)
                g_setup = g_setup "    " v "." g_mname[t, i] " = " e ";\n"
                continue
            }
            na = g_count(g_msize[t, i])
            if (na < 1) { g_cant = "array size " g_msize[t, i] " of " t; return "0" }
            for (pn = 0; pn < na; pn++) {
                e = g_synth(g_mtype[t, i], path "." g_mname[t, i] "[" pn "]", f, lvl + 1)
                g_setup = g_setup "    " v "." g_mname[t, i] "[" pn "] = " e ";\n"
            }
        }
        return v
    }
    if ((mk in fn_index) && fn_ret[fn_index[mk]] == t && mk != f) {
        na = split_args(fn_args[fn_index[mk]], a)
        e = ""
        for (i = 1; i <= na; i++) {
            pn = a[i]; sub(/^.*[ \t]/, "", pn)
            e = e (i > 1 ? ", " : "") g_synth(arg_type(a[i], mk), path "." pn, mk, lvl + 1)
        }
        return mk "(" e ")"
    }
    if ((t in struct_known) && !(t in struct_bad) && struct_n[t] > 0) {
        v = "pfg_a" (++g_nloc)
        g_setup = g_setup "    " t " " v ";\n"
        for (i = 1; i <= struct_n[t]; i++) {
            e = g_synth(struct_mtype[t, i], path "." struct_mname[t, i], f, lvl + 1)
            g_setup = g_setup "    " v "." struct_mname[t, i] " = " e ";\n"
        }
        return v
    }
    g_cant = "argument type " t
    return "0"
}

# output statements for every scalar leaf of value v of type t
function g_leaves(v, t, lvl,    i, j) {
    if (lvl > 8) die("struct nesting too deep in " v)
    if (t == "pf_real" || t == "int") {
        if (out == "glsl") g_body = g_body "    pfg_out.v[o + " g_nout "u] = float(" v ");\n"
        else if (t == "int") g_body = g_body "    out[" g_nout "] = (double)(float)" v ";\n"
        else g_body = g_body "    out[" g_nout "] = (double)" v ";\n"
        g_nout++
        return
    }
    if ((t in struct_bad) && g_mn[t] > 0) {
        for (i = 1; i <= g_mn[t]; i++) {
            if (g_msize[t, i] == "") { g_leaves(v "." g_mname[t, i], g_mtype[t, i], lvl + 1); continue }
            for (j = 0; j < g_count(g_msize[t, i]); j++) g_leaves(v "." g_mname[t, i] "[" j "]", g_mtype[t, i], lvl + 1)
        }
        return
    }
    if ((t in struct_known) && !(t in struct_bad) && struct_n[t] > 0) {
        for (i = 1; i <= struct_n[t]; i++) g_leaves(v "." struct_mname[t, i], struct_mtype[t, i], lvl + 1)
        return
    }
    g_cant = "result type " t
}

END {
    if (failed) exit 1
    nt = split(targets, tt, /[ \t]+/)
    for (i = 1; i <= nt; i++) if (tt[i] != "") g_target[tt[i]] = 1
    if (out == "glsl") {
        print "/* Generated by tests/gpu/gen.awk for " targets ". Do not edit. */"
        print "#version 450"
        print "#extension GL_GOOGLE_include_directive : require"
        print "#define PF_GLSL 1"
        ni = split(includes, inc, /[ \t]+/)
        for (i = 1; i <= ni; i++) if (inc[i] != "") printf "#include \"%s\"\n", inc[i]
        print "layout(local_size_x = 64) in;"
        print "layout(std430, binding = 0) readonly buffer PfgIn { float v[]; } pfg_in;"
        print "layout(std430, binding = 1) writeonly buffer PfgOut { float v[]; } pfg_out;"
        print "layout(push_constant) uniform PfgPc { uint fn; uint n; } pfg_pc;"
        print ""
    } else {
        print "/* Generated by tests/gpu/gen.awk (C wrappers of every GLSL-callable function). Do not edit. */"
        print "#include \"pfg_fns.h\""
        for (i = 1; i <= nf; i++) if (!(fn_file[i] in g_inc)) { g_inc[fn_file[i]] = 1; h = fn_file[i]; sub(/^.*\//, "", h); printf "#include \"%s\"\n", h }
        print ""
    }
    nh = 0
    for (i = 1; i <= nf; i++) {
        if (fn_region[i] == "c") continue
        h = fn_file[i]; sub(/^.*\//, "", h)
        if ((out == "glsl" || nt > 0) && !(h in g_target)) continue
        g_slots = ""; g_setup = ""; g_body = ""; g_nin = 0; g_nout = 0; g_nloc = 0; g_cant = ""
        na = split_args(fn_args[i], a)
        call = ""
        for (j = 1; j <= na; j++) {
            pn = a[j]; sub(/^.*[ \t]/, "", pn)
            ty = arg_type(a[j], fn_name[i])
            if (ty == "?") { g_cant = cant; continue }
            call = call (j > 1 ? ", " : "") g_synth(ty, pn, fn_name[i], 0)
        }
        call = fn_name[i] "(" call ")"
        if (fn_ret[i] == "pf_real" || fn_ret[i] == "int") g_leaves(call, fn_ret[i], 0)
        else { g_setup = g_setup "    " fn_ret[i] " pfg_r = " call ";\n"; g_leaves("pfg_r", fn_ret[i], 0) }
        if (g_cant != "") { g_skip = g_skip " " fn_name[i] "(" g_cant ")"; continue }
        if (!(h in h_count)) h_count[h] = 0
        k = h_count[h]++
        if (out == "glsl") {
            printf "void pfg_f%d(uint i)\n{   /* %s */\n    uint b = i * %du, o = i * %du;\n%s%s}\n\n", k, fn_name[i], g_nin, g_nout, g_setup, g_body
            nglsl++
        } else {
            printf "static void pfg_c_%s(const float *in, double *out)\n{\n", fn_name[i]
            if (g_nin == 0) print "    (void)in;"
            printf "%s%s}\n\n", g_setup, g_body
            tab = tab sprintf("    { \"%s\", \"%s\", %d, %d, %d, \"%s\", pfg_c_%s },\n", fn_name[i], h, k, g_nin, g_nout, substr(g_slots, 2), fn_name[i])
        }
    }
    if (out == "glsl") {
        print "void main()\n{\n    uint i = gl_GlobalInvocationID.x;\n    if (i >= pfg_pc.n) return;\n    switch (pfg_pc.fn) {"
        for (k = 0; k < nglsl; k++) printf "    case %du: pfg_f%d(i); break;\n", k, k
        print "    default: break;\n    }\n}"
    } else {
        print "const pfg_fn PFG_TABLE[] = {\n" tab "    { 0, 0, 0, 0, 0, 0, 0 }\n};"
        print "const char PFG_SKIPPED[] = \"" substr(g_skip, 2) "\";"
    }
    exit 0
}
