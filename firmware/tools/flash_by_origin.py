#!/usr/bin/env python3
"""Flash used by shadeline's code in a firmware ELF, attributed through inlining.

Why not symbol sizes: with fat LTO the renderer is inlined into the demo's functions
(`render_line` into the measuring loop, `PreparedFixed::new` into `main`), so summing
symbols named `shadeline::…` misses most of it. Instead every instruction of `.text` is
looked up with binutils' `addr2line -i` (llvm-tools ships no symbolizer), which gives the whole chain of functions it was
inlined from, and attributed by this rule:

  shadeline   a frame of the chain is in shadeline's own source (the repository's src/);
              core/alloc generics inlined into shadeline code count here too
  deps        otherwise, a frame is in one of shadeline's dependencies (libm, fixed, wide,
              heapless, az, typenum, bytemuck, half): their functions only exist for it
  builtins    compiler-builtins: soft float, 64-bit division, memcpy (shared with the demo)
  demo        everything else: the demo, its runtime (cortex-m-rt, riscv-rt, semihosting)

Each instruction's size is the distance to the next address in the disassembly.

Usage: flash_by_origin.py ELF REPO_ROOT LLVM_BIN_DIR (where llvm-objdump is)  ->  prints
`key=value` fields (what .ci/firmware reads). To see where shadeline's bytes go:

  --by function   a table of shadeline's bytes by the outermost shadeline function of each
                  instruction's chain (the function its code is inlined into, or its own
                  out-of-line copy); also `file` (innermost shadeline source file) and `line`
                  (innermost shadeline file:line). Comma-separated for several tables.
  --ran LABEL=FILE  splits shadeline's bytes by whether they ran: FILE is the output of
                  `tools/profile ELF --region R --by addr --top 0` (every executed address of
                  that region); each byte goes to the first LABEL whose FILE lists its
                  address, else to `never ran`. Repeatable, e.g. the render, the prepare and
                  the scene's construction of the M0 demo:

    tools/profile $ELF --region render-fixed --by addr --top 0 > render.txt   (and so on)
    tools/flash_by_origin.py $ELF .. $LLVM_BIN --by function \
        --ran render=render.txt --ran prepare=prepare.txt --ran scene=scene.txt
"""

import argparse
import os
import re
import subprocess
from collections import defaultdict

DEPS = ("libm-", "fixed-", "wide-", "heapless-", "az-", "typenum-", "bytemuck-", "half-")


def executed(path):
    """The addresses of a `tools/profile --by addr` table."""
    out = set()
    with open(path) as f:
        for line in f:
            m = re.match(r"\s*\d+\s+[\d.]+%\s+([0-9a-f]{8})\s*$", line)
            if m:
                out.add(int(m.group(1), 16))
    return out


def own_key(by, own, root):
    """The table key of an instruction whose chain's shadeline frames are `own`
    (innermost first)."""
    if by == "function":
        return own[-1][0]
    path, _, line = own[0][1].rpartition(":")
    path = os.path.relpath(os.path.realpath(path), root)
    return path if by == "file" else f"{path}:{line.split(' ')[0]}"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("elf")
    ap.add_argument("root", help="the repository's root (shadeline's src/ is under it)")
    ap.add_argument("bindir", help="the directory of llvm-objdump")
    ap.add_argument("--by", default="", help="function, file, line (comma-separated)")
    ap.add_argument("--ran", action="append", default=[], metavar="LABEL=FILE",
                    help="executed addresses of a region, from `tools/profile --by addr`")
    ap.add_argument("--top", type=int, default=30, help="rows per table (0: all)")
    args = ap.parse_args()
    elf, root, bindir = args.elf, os.path.realpath(args.root), args.bindir
    runs = []
    for spec in args.ran:
        label, sep, path = spec.partition("=")
        if not sep:
            ap.error(f"--ran {spec}: expected LABEL=FILE")
        runs.append((label, executed(path)))
    tables = [b for b in args.by.split(",") if b]
    for b in tables:
        if b not in ("function", "file", "line"):
            ap.error(f"--by {b}: expected function, file or line")
    own = os.path.join(root, "src") + os.sep
    dis = subprocess.run(
        [os.path.join(bindir, "llvm-objdump"), "-d", "--no-show-raw-insn", "-j", ".text", elf],
        check=True, capture_output=True, text=True).stdout
    addrs = [int(m.group(1), 16) for m in re.finditer(r"^\s*([0-9a-f]+):", dis, re.M)]
    sizes = {}
    for a, b in zip(addrs, addrs[1:]):
        sizes[a] = b - a
    if addrs:
        sizes[addrs[-1]] = 2
    query = "".join(f"0x{a:x}\n" for a in sizes)
    out = subprocess.run(
        ["addr2line", "-a", "-i", "-f", "-C", "-e", elf],
        input=query, check=True, capture_output=True, text=True).stdout
    chains = {}
    current = None
    lines = out.splitlines()
    i = 0
    while i < len(lines):
        if re.fullmatch(r"0x[0-9a-f]+", lines[i]):
            current = int(lines[i], 16)
            chains[current] = []
            i += 1
            continue
        chains[current].append((lines[i], lines[i + 1] if i + 1 < len(lines) else ""))
        i += 2
    totals = {"shadeline": 0, "deps": 0, "builtins": 0, "demo": 0}
    by_key = {b: defaultdict(int) for b in tables}
    by_run = defaultdict(int)
    for addr, size in sizes.items():
        frames = chains.get(addr, [])
        files = [f for _, f in frames]
        mine = [(n, f) for n, f in frames if os.path.realpath(f.rsplit(":", 1)[0]).startswith(own)]
        if mine:
            kind = "shadeline"
            for b in tables:
                by_key[b][own_key(b, mine, root)] += size
            if runs:
                by_run[next((label for label, seen in runs if addr in seen), "never ran")] += size
        elif any(any(f"/{d}" in f for d in DEPS) for f in files):
            kind = "deps"
        elif any("compiler_builtins" in n or "compiler-builtins" in f for n, f in frames):
            kind = "builtins"
        else:
            kind = "demo"
        totals[kind] += size
    text = sum(sizes.values())
    print(" ".join(f"{k}={v}" for k, v in totals.items()) + f" text={text}")
    if runs:
        print("\n## shadeline's bytes by where they ran")
        for label in [label for label, _ in runs] + ["never ran"]:
            print(f"  {by_run[label]:7}  {label}")
    for b in tables:
        rows = sorted(by_key[b].items(), key=lambda kv: -kv[1])
        print(f"\n## shadeline's bytes by {b} ({len(rows)} rows)")
        for key, n in rows[: args.top or None]:
            print(f"  {n:7}  {key}")


if __name__ == "__main__":
    main()
