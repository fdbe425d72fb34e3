# bench/gpu/spirv_ops.awk - the SPIR-V cost of a shader's entry point, the one rule of the bench:
# reads `spirv-dis` of a module after `spirv-opt -O` and prints "ops branches" for the entry
# point's function: every instruction except loads, stores, access chains, variables, labels,
# branches, merges, returns, parameters and kill (bookkeeping a GPU compiler folds or that
# is not arithmetic); branches = OpBranchConditional + OpSwitch. Used by bench/gpu/count.sh
# (compute wrappers of every public function) and bench/frame/run.sh (the frame's fragment shaders).
/OpEntryPoint/ { for (i = 1; i <= NF; i++) if ($i ~ /^%/) { ep = $i; break } }
$1 == ep && $3 == "OpFunction" { inmain = 1; next }
inmain && $1 == "OpFunctionEnd" { inmain = 0; next }
inmain {
    op = ($2 == "=") ? $3 : $1
    if (op == "OpBranchConditional" || op == "OpSwitch") br++
    if (op ~ /^Op(Load|Store|AccessChain|InBoundsAccessChain|Variable|Label|Branch|BranchConditional|Switch|SelectionMerge|LoopMerge|Return|ReturnValue|FunctionParameter|Kill)$/) next
    n++
}
END { printf "%d %d\n", n, br }
