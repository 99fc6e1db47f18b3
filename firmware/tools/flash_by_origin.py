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
Usage: flash_by_origin.py ELF REPO_ROOT LLVM_BIN_DIR (where llvm-objdump is)  ->  prints `key=value` fields.
"""

import os
import re
import subprocess
import sys

DEPS = ("libm-", "fixed-", "wide-", "heapless-", "az-", "typenum-", "bytemuck-", "half-")


def main():
    elf, root, bindir = sys.argv[1], os.path.realpath(sys.argv[2]), sys.argv[3]
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
        ["addr2line", "-a", "-i", "-f", "-e", elf],
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
    for addr, size in sizes.items():
        frames = chains.get(addr, [])
        files = [f for _, f in frames]
        if any(os.path.realpath(f.rsplit(":", 1)[0]).startswith(own) for f in files):
            kind = "shadeline"
        elif any(any(f"/{d}" in f for d in DEPS) for f in files):
            kind = "deps"
        elif any("compiler_builtins" in n or "compiler-builtins" in f for n, f in frames):
            kind = "builtins"
        else:
            kind = "demo"
        totals[kind] += size
    text = sum(sizes.values())
    print(" ".join(f"{k}={v}" for k, v in totals.items()) + f" text={text}")


if __name__ == "__main__":
    main()
