// Runs a wasm32-wasip1 program (a test binary, say) under Node's WASI, with the arguments
// and environment it was given, and exits with the program's exit code. Cargo uses it as
// the target runner: CARGO_TARGET_WASM32_WASIP1_RUNNER="node checks/wasi-run.mjs".
//
// The program sees the current directory as `.` (Node's WASI does not sandbox it: run only
// programs you trust, such as this repository's tests). A trap (a panic, under wasm's
// panic=abort) is reported and exits with 101, like a failed Rust test binary.
import { readFile } from "node:fs/promises";
import { argv, env, exit } from "node:process";
import { WASI } from "node:wasi";

const [program, ...args] = argv.slice(2);
if (!program) {
  console.error("usage: node checks/wasi-run.mjs PROGRAM.wasm [ARGS...]");
  exit(2);
}
const wasi = new WASI({
  version: "preview1",
  args: [program, ...args],
  env,
  preopens: { ".": "." },
  returnOnExit: true,
});
const module = await WebAssembly.compile(await readFile(program));
const instance = await WebAssembly.instantiate(module, wasi.getImportObject());
let code;
try {
  code = wasi.start(instance);
} catch (e) {
  console.error(`wasi-run: ${program} trapped: ${e}`);
  code = 101;
}
exit(code);
