# One mesh larger than memory as a Snakemake workflow: the stages of
# `lodbake-simplify --memory-limit` as jobs, so that the blocks run side by
# side on different machines sharing the work folder. The output is byte for
# byte what the one-shot run writes (docs/simplify.md "Larger than memory").
#
#   snakemake -s workflow/out_of_core.smk --cores N \
#     --config mesh=BIG.ply out=OUT.ply limit=2G target="--ratio 0.1" \
#              [work=DIR] [simplify=PATH] [threads=T]
#
# The split is a checkpoint: how many blocks there are is known once it has
# run (plan.json), and the merge waits for every one of them.
import json
import os
import shlex

from snakemake.exceptions import WorkflowError

for key in ("mesh", "out", "limit", "target"):
    if key not in config:
        raise WorkflowError(
            "lodbake out-of-core workflow: give mesh=, out=, limit= and target= with --config"
        )
MESH = str(config["mesh"])
OUT = str(config["out"])
WORK = str(config.get("work", OUT + ".work"))
SIMPLIFY = shlex.quote(str(config.get("simplify", "lodbake-simplify")))
THREADS = int(config.get("threads", 1))
PLAN = os.path.join(WORK, "plan.json")


def block_outputs(wildcards):
    with open(checkpoints.split.get().output[0]) as plan:
        blocks = len(json.load(plan)["block_triangles"])
    return [os.path.join(WORK, "block_%04d.out" % b) for b in range(blocks)]


localrules:
    all,


rule all:
    input:
        OUT,


checkpoint split:
    input:
        MESH,
    output:
        PLAN,
    params:
        limit=str(config["limit"]),
        target=str(config["target"]),
    shell:
        "{SIMPLIFY} {input:q} --stage split --work {WORK:q} --memory-limit {params.limit} "
        "{params.target} --quiet > /dev/null"


rule block:
    input:
        PLAN,
    output:
        os.path.join(WORK, "block_{n}.out"),
    wildcard_constraints:
        n="[0-9]{4}",
    threads: THREADS
    shell:
        "{SIMPLIFY} --stage block --block {wildcards.n} --work {WORK:q} "
        "--threads {threads} --quiet > /dev/null"


rule merge:
    input:
        block_outputs,
    output:
        OUT,
    threads: THREADS
    shell:
        "{SIMPLIFY} --stage merge --work {WORK:q} -o {output:q} --threads {threads} --quiet "
        "> /dev/null"
