# gen.awk - generate a translation unit that calls every public function of some headers.
#
# Part of `make portability` (see docs/porting.md). POSIX awk: runs under mawk, gawk, busybox.
#
# usage: awk -v mode=c|cuda|glsl -v targets="pf_a.h pf_b.h" [-v includes="pf_core.h pf_a.h"]
#            -f gen.awk include/pf_*.h
#   Every header named on the command line is read, so that struct layouts and makers defined
#   in one header are known when another uses them. Wrappers are generated only for the public
#   functions of the headers in `targets` (basenames). `includes` lists the #include lines to
#   emit (basenames, in order); empty means "emit none" (the caller pastes the header text).
#
# What counts as a public function: a declaration that starts a line with
#     PF_DEF <return type> pf_<name>(<args>)
# (args may continue on later lines; the declaration is joined up to its closing paren).
# Names not starting pf_ (private helpers are pfi_...) are skipped. Comments are ignored.
#
# Stamps: a function-like macro whose body holds PF_DEF declarations, e.g.
#     #define PFI_STAMP(T, F) \
#         PF_DEF T F##_lerp(T a, T b, pf_real t) { ... } \
#         PF_DEF T F##_scale(T a, pf_real w) { ... }
# is remembered, and a line that invokes it, `PFI_STAMP(pf_x, pf_x)`, declares what the
# expansion declares (parameters replaced as whole tokens, ## pasted), at the invocation's line
# and region, as if the functions were written out. Other #define lines are ignored.
#
# Arguments are synthesised from their type:
#   pf_real            a value read from the input buffer (in[k] / pfp_in.v[k]) so nothing folds
#   int                (int)(input * 16)
#   struct type T      T_make(...) if a public T_make returning T exists (pf_vec3_make, ...),
#                      else a local of type T whose members are each synthesised and assigned
#   anything else      error: "gen.awk: cannot synthesise ..." naming the function; exit 1
# Results: pf_real is added to an accumulator; a struct result is stored and every pf_real
# (or int) leaf member is added, so no member's computation can be dead-code eliminated.
#
# Functions inside `#ifndef PF_GLSL` (or `#if !defined(PF_GLSL)`) are C-only: they are not
# called from GLSL, and when they take pointers (CPU-only buffer walkers) they are skipped
# instead of failing. Functions inside `#ifdef PF_GLSL` are called from GLSL only.
#
# Output per function (mode c shown):
#     pf_real pfp_pf_smith_nu(const pf_real *in)
#     {
#         pf_real pfp_acc = PF_R(0.0);
#         pfp_acc += pf_smith_nu(pf_vec3_make(in[0], in[1], in[2]), pf_slope_stats_make(...));
#         return pfp_acc;
#     }
# followed by a mode-specific driver: PFP_FUNCTIONS table (c), a __global__ kernel (cuda), or
# SSBO declarations and main() (glsl).

function trim(s) { sub(/^[ \t]+/, "", s); sub(/[ \t]+$/, "", s); return s }

function die(msg) { print "gen.awk: " msg > "/dev/stderr"; failed = 1; exit 1 }

# Remove /* */ and // comments; block comments may span lines (state in incomment).
function strip_comments(s,    out, p) {
    out = ""
    while (s != "") {
        if (incomment) {
            p = index(s, "*/")
            if (p == 0) return out
            s = substr(s, p + 2); incomment = 0
        } else {
            p = index(s, "/*")
            q = index(s, "//")
            if (q > 0 && (p == 0 || q < p)) return out substr(s, 1, q - 1)
            if (p == 0) return out s
            out = out substr(s, 1, p - 1) " "
            s = substr(s, p + 2); incomment = 1
        }
    }
    return out
}

# Region of the current line: "c" (not compiled as GLSL), "glsl" (GLSL only) or "all".
function region(    i) {
    for (i = 1; i <= depth; i++) if (cond[i] == "c") return "c"
    for (i = 1; i <= depth; i++) if (cond[i] == "glsl") return "glsl"
    return "all"
}

function directive(s,    d, rest) {
    s = trim(substr(trim(s), 2))
    d = s; sub(/[ \t(!].*$/, "", d)
    rest = trim(substr(s, length(d) + 1))
    gsub(/[ \t]+/, "", rest)
    if (d == "ifndef" || d == "ifdef" || d == "if") {
        depth++
        if ((d == "ifndef" && rest == "PF_GLSL") || (d == "if" && (rest == "!defined(PF_GLSL)" || rest == "!defined PF_GLSL")))
            cond[depth] = "c"
        else if ((d == "ifdef" && rest == "PF_GLSL") || (d == "if" && (rest == "defined(PF_GLSL)" || rest == "definedPF_GLSL")))
            cond[depth] = "glsl"
        else
            cond[depth] = "n"
    } else if (d == "else") {
        if (cond[depth] == "c") cond[depth] = "glsl"
        else if (cond[depth] == "glsl") cond[depth] = "c"
    } else if (d == "elif") {
        if (cond[depth] == "glsl") cond[depth] = "c"
    } else if (d == "endif") {
        if (depth > 0) depth--
    }
}

# Index just past the paren matching the first "(" in s, or 0 if not closed yet.
function close_paren(s,    i, c, lv, seen) {
    lv = 0; seen = 0
    for (i = 1; i <= length(s); i++) {
        c = substr(s, i, 1)
        if (c == "(") { lv++; seen = 1 }
        else if (c == ")") { lv--; if (seen && lv == 0) return i }
    }
    return 0
}

function record_decl(s, file, line, reg,    p, e, head, args, name, ret, n, t) {
    p = index(s, "(")
    e = close_paren(s)
    head = trim(substr(s, 1, p - 1))
    args = trim(substr(s, p + 1, e - p - 1))
    sub(/^PF_DEF[ \t]+/, "", head)
    n = split(head, t, /[ \t*]+/)
    name = t[n]
    ret = trim(substr(head, 1, length(head) - length(name)))
    if (name !~ /^pf_[A-Za-z0-9]/) return
    if (name in fn_index) return                    # a prototype, then its definition
    gsub(/(^|[ \t])(static|inline|const)[ \t]+/, " ", ret); ret = trim(ret)
    nf++
    fn_name[nf] = name; fn_ret[nf] = ret; fn_args[nf] = args
    fn_file[nf] = file; fn_line[nf] = line; fn_region[nf] = reg
    fn_index[name] = nf
}

function record_member(sname, s,    n, t, i, type, names, k, m, first) {
    s = trim(s)
    if (s == "") return
    if (s !~ /;$/) { struct_bad[sname] = s; return }
    sub(/;$/, "", s)
    # "type a, b" -> type is everything before the last word of the first declarator
    k = index(s, ",")
    first = (k > 0) ? trim(substr(s, 1, k - 1)) : s
    n = split(first, t, /[ \t]+/)
    type = ""
    for (i = 1; i < n; i++) type = type (i > 1 ? " " : "") t[i]
    names = t[n] (k > 0 ? substr(s, k) : "")
    m = split(names, t, /,/)
    for (i = 1; i <= m; i++) {
        if (trim(t[i]) ~ /[^A-Za-z0-9_]/) { struct_bad[sname] = s; return }
        struct_n[sname]++
        struct_mname[sname, struct_n[sname]] = trim(t[i])
        struct_mtype[sname, struct_n[sname]] = type
    }
}

# A stamp's body with its parameters replaced by the arguments and ## pasted; every PF_DEF
# declaration in it is recorded.
function expand_stamp(call, file, line, reg,    p, e, name, na, a, np, q, i, body, out, tok) {
    p = index(call, "("); e = close_paren(call)
    name = trim(substr(call, 1, p - 1))
    na = split_args(substr(call, p + 1, e - p - 1), a)
    np = split(stamp_params[name], q, /[ \t]*,[ \t]*/)
    if (na != np) die(file ":" line ": " name " takes " np " arguments, given " na)
    for (i = 1; i <= np; i++) arg_of[q[i]] = a[i]
    body = stamp_body[name]; out = ""
    while (match(body, /[A-Za-z_][A-Za-z0-9_]*/)) {
        tok = substr(body, RSTART, RLENGTH)
        out = out substr(body, 1, RSTART - 1) ((tok in arg_of) ? arg_of[tok] : tok)
        body = substr(body, RSTART + RLENGTH)
    }
    out = out body
    for (i = 1; i <= np; i++) delete arg_of[q[i]]
    gsub(/[ \t]*##[ \t]*/, "", out)
    while ((p = index(out, "PF_DEF ")) > 0) {
        out = substr(out, p)
        e = index(substr(out, 8), "PF_DEF ")
        record_decl(e ? substr(out, 1, e + 6) : out, file, line, reg)
        out = substr(out, 8)
    }
}

# A complete #define: remembered as a stamp when its body holds PF_DEF.
function define_done(s,    name, params) {
    sub(/^[ \t]*#[ \t]*define[ \t]+/, "", s)
    if (!match(s, /^[A-Za-z_][A-Za-z0-9_]*\(/)) return
    name = substr(s, 1, RLENGTH - 1)
    params = substr(s, RLENGTH + 1); sub(/\).*$/, "", params)
    s = substr(s, RLENGTH + 1); sub(/^[^)]*\)/, "", s)
    if (index(s, "PF_DEF") == 0) return
    stamp_params[name] = trim(params); stamp_body[name] = s
}

FNR == 1 {
    file = FILENAME; sub(/^.*\//, "", file)
    depth = 0; incomment = 0; pending = ""; instruct = ""; indefine = ""; pend_stamp = 0
    nfiles++; file_order[nfiles] = file
}

{
    raw = $0
    sub(/\r$/, "", raw)                             # CRLF checkouts
    s = strip_comments(raw)
    if (indefine != "") {                            # continuation lines of a #define
        indefine = indefine " " s
        if (indefine ~ /\\[ \t]*$/) sub(/\\[ \t]*$/, "", indefine)
        else { define_done(indefine); indefine = "" }
        next
    }
    if (pending != "") {
        pending = pending " " trim(s)
        if (close_paren(pending)) {
            if (pend_stamp) expand_stamp(pending, file, pend_line, pend_reg)
            else record_decl(pending, file, pend_line, pend_reg)
            pending = ""; pend_stamp = 0
        }
        next
    }
    if (s ~ /^[ \t]*#[ \t]*define[ \t]/) {
        if (s ~ /\\[ \t]*$/) { indefine = s; sub(/\\[ \t]*$/, "", indefine) }
        else define_done(s)
        next
    }
    if (s ~ /^[ \t]*#/) { directive(s); next }
    if (match(s, /^[ \t]*[A-Za-z_][A-Za-z0-9_]*[ \t]*\(/)) {
        callee = substr(s, RSTART, RLENGTH); sub(/[ \t]*\($/, "", callee); callee = trim(callee)
        if (callee in stamp_body) {                # a stamp: declares what its expansion declares
            s = trim(s)
            if (close_paren(s)) expand_stamp(s, file, FNR, region())
            else { pending = s; pend_line = FNR; pend_reg = region(); pend_stamp = 1 }
            next
        }
    }
    if (instruct != "") {
        if (s ~ /PF_STRUCT_END[ \t]*\(/) { instruct = ""; next }
        record_member(instruct, s)
        next
    }
    if (s ~ /PF_STRUCT_BEGIN[ \t]*\(/) {
        instruct = s; sub(/^.*PF_STRUCT_BEGIN[ \t]*\([ \t]*/, "", instruct); sub(/[ \t]*\).*$/, "", instruct)
        struct_n[instruct] = 0; struct_known[instruct] = 1
        next
    }
    if (s ~ /^[ \t]*PF_DEF[ \t]/) {
        s = trim(s)
        if (index(s, "(") && close_paren(s)) record_decl(s, file, FNR, region())
        else { pending = s; pend_line = FNR; pend_reg = region() }
    }
}

# ------------------------------------------------------------------ synthesis
function input(    k) { k = nin % 16; nin++; return (mode == "glsl") ? "pfp_in.v[" k "]" : "in[" k "]" }

function to_int(x) { return (mode == "glsl") ? "int(" x " * 16.0)" : "(int)(" x " * PF_R(16.0))" }

# Expression of type t for an argument of function f; may append declarations to `setup`.
function synth(t, f, lvl,    mk, i, args, a, na, v, e) {
    if (lvl > 8) die("type nesting too deep synthesising " t " for " f)
    if (t == "pf_real") return input()
    if (t == "int") return to_int(input())
    mk = t "_make"
    if ((mk in fn_index) && fn_ret[fn_index[mk]] == t && mk != f) {
        na = split_args(fn_args[fn_index[mk]], a)
        e = ""
        for (i = 1; i <= na; i++) e = e (i > 1 ? ", " : "") synth(arg_type(a[i], mk), mk, lvl + 1)
        return mk "(" e ")"
    }
    if ((t in struct_known) && !(t in struct_bad) && struct_n[t] > 0) {
        v = "pfp_a" (++nloc)
        setup = setup "    " t " " v ";\n"
        for (i = 1; i <= struct_n[t]; i++) {
            e = synth(struct_mtype[t, i], f, lvl + 1)
            setup = setup "    " v "." struct_mname[t, i] " = " e ";\n"
        }
        return v
    }
    cant = "type '" t "'"
    return ""
}

# Split an argument list on top-level commas into a[]; returns the count ("void" -> 0).
function split_args(s, a,    n, i, c, lv, cur) {
    s = trim(s)
    if (s == "" || s == "void") return 0
    n = 0; lv = 0; cur = ""
    for (i = 1; i <= length(s); i++) {
        c = substr(s, i, 1)
        if (c == "(") lv++
        if (c == ")") lv--
        if (c == "," && lv == 0) { a[++n] = trim(cur); cur = "" } else cur = cur c
    }
    a[++n] = trim(cur)
    return n
}

# Type of one parameter declaration "const pf_real x" -> "pf_real"; "" if unsupported.
function arg_type(p, f,    n, t, i, ty) {
    if (p ~ /[*\[&]/ || p ~ /\.\.\./) { cant = "parameter '" p "'"; return "?" }
    gsub(/(^|[ \t])(const|in|register)[ \t]+/, " ", p)
    n = split(trim(p), t, /[ \t]+/)
    if (n < 2) { cant = "parameter '" p "' (no name?)"; return "?" }
    ty = t[1]
    for (i = 2; i < n; i++) ty = ty " " t[i]
    return ty
}

# Append "+= leaf" lines for every scalar leaf of a value v of type t.
function add_leaves(v, t, lvl,    i) {
    if (lvl > 8) die("struct nesting too deep in " v)
    if (t == "pf_real") { body = body "    pfp_acc += " v ";\n"; return 1 }
    if (t == "int") { body = body "    pfp_acc += PF_R(" v ");\n"; return 1 }
    if ((t in struct_known) && !(t in struct_bad) && struct_n[t] > 0) {
        for (i = 1; i <= struct_n[t]; i++)
            if (!add_leaves(v "." struct_mname[t, i], struct_mtype[t, i], lvl + 1)) return 0
        return 1
    }
    return 0
}

function wanted(i) {
    if (!(fn_file[i] in target)) return 0
    if (mode == "glsl") return fn_region[i] != "c"
    return fn_region[i] != "glsl"
}

function emit_function(i,    f, na, a, j, ty, e, call, where) {
    f = fn_name[i]; where = fn_file[i] ":" fn_line[i]
    setup = ""; body = ""; nloc = 0; nin = 0; cant = ""
    na = split_args(fn_args[i], a)
    call = ""
    for (j = 1; j <= na; j++) {
        ty = arg_type(a[j], f)
        e = (ty == "?") ? "" : synth(ty, f, 0)
        if (e == "") {
            if (fn_region[i] == "c" && cant ~ /^parameter/) {
                skipped = skipped sprintf("/* %s %s: C-only, %s not synthesised; not called */\n", where, f, cant)
                return
            }
            die(where ": cannot synthesise argument " j " of " f ": " cant)
        }
        call = call (j > 1 ? ", " : "") e
    }
    call = f "(" call ")"
    ret = fn_ret[i]
    if (ret == "void") body = "    " call ";\n"
    else if (ret == "pf_real" || ret == "int") { if (!add_leaves(call, ret, 0)) die("?") }
    else if ((ret in struct_known) && !(ret in struct_bad) && struct_n[ret] > 0) {
        body = "    " ret " pfp_r = " call ";\n"
        if (!add_leaves("pfp_r", ret, 0)) die(where ": cannot read back result type '" ret "' of " f)
    } else die(where ": cannot use return type '" ret "' of " f)

    # a function of no pf_real argument reads no input: keep -Wunused-parameter quiet
    if (nin == 0 && mode != "glsl") setup = "    (void)in;\n" setup
    nout++; out_name[nout] = f
    if (mode == "glsl") printf "float pfp_%s()\n", f
    else if (mode == "cuda") printf "__device__ pf_real pfp_%s(const pf_real *in)\n", f
    else printf "pf_real pfp_%s(const pf_real *in);\npf_real pfp_%s(const pf_real *in)\n", f, f
    printf "{   /* %s */\n    pf_real pfp_acc = PF_R(0.0);\n%s%s    return pfp_acc;\n}\n\n", where, setup, body
}

END {
    if (failed) exit 1
    if (pending != "") die(file ":" pend_line ": unterminated declaration: " pending)
    if (mode != "c" && mode != "cuda" && mode != "glsl") die("mode must be c, cuda or glsl")
    nt = split(targets, tt, /[ \t]+/)
    for (i = 1; i <= nt; i++) if (tt[i] != "") target[tt[i]] = 1
    ni = split(includes, inc, /[ \t]+/)

    printf "/* Generated by tests/portability/gen.awk (mode %s) for: %s. Do not edit. */\n", mode, targets
    if (mode == "glsl") {
        if (ni > 0) {
            print "#version 450"
            print "#extension GL_GOOGLE_include_directive : require"
            print "#define PF_GLSL 1"
        }
    }
    for (i = 1; i <= ni; i++) if (inc[i] != "") printf "#include \"%s\"\n", inc[i]
    print ""
    if (mode == "glsl") {
        print "layout(local_size_x = 1) in;"
        print "layout(std430, binding = 0) readonly buffer PfpIn { float v[]; } pfp_in;"
        print "layout(std430, binding = 1) writeonly buffer PfpOut { float v[]; } pfp_out;"
        print ""
    }
    for (i = 1; i <= nf; i++) if (wanted(i)) emit_function(i)
    if (failed) exit 1
    printf "%s", skipped
    if (mode == "glsl") {
        print "void main()\n{"
        for (i = 1; i <= nout; i++) printf "    pfp_out.v[%d] = pfp_%s();\n", i - 1, out_name[i]
        print "}"
    } else if (mode == "cuda") {
        print "__global__ void pfp_kernel(const pf_real *in, pf_real *out)\n{"
        for (i = 1; i <= nout; i++) printf "    out[%d] = pfp_%s(in);\n", i - 1, out_name[i]
        print "}"
    } else {
        print "#define PFP_COUNT " nout
        print "#define PFP_FUNCTIONS \\"
        for (i = 1; i <= nout; i++) printf "    PFP_FN(%s) \\\n", out_name[i]
        print "    /* end of PFP_FUNCTIONS */"
    }
}
