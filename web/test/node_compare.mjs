// Runs every catalogue system with every method it takes in the WebAssembly build, as
// crates/physicskit-wasm/src/bin/lab_reference.rs does natively, and compares the final
// state, clock and energy error bit for bit with the native output. The adaptive methods are
// among them (at the lab's default tolerance, and the native lines with a `tol` at that
// tolerance): taylor runs its interpreted recurrences in wasm (no Cranelift there) and may
// run them compiled natively, and its error-free products use one FMA natively where the CPU
// has it and Dekker's product in wasm; both are exact. Where the standard library enters
// (dop853's step-size controller takes err^(1/8) by `powf`; taylor's recurrences for sin and
// cos start from the libm values of the series' first term), the runs agree within MAX_DIFF
// below (measured: at most 2.8e-15 of the state, dop853 on the rolling rattleback: its steps
// differ by the last bit of a step size, not by the numerics).
//
//   node web/test/node_compare.mjs WASM_FILE NATIVE_OUTPUT
//
// Bit-identical is the aim and what most systems give: the integrators, the forces and the
// slice trig (core/trig.rs) are our own code, compiled without fma, so both targets round
// every operation alike. Where a system calls the standard library's transcendentals
// (`exp` in the Toda force; `sin`, `exp`, `atan`, `cosh` in the FPUT and sine-Gordon initial
// data), native code calls glibc and wasm Rust's port of musl's libm: both are faithfully
// rounded, but may differ in the last bit. Such runs must agree to MAX_DIFF relative to
// the state's largest entry (entries near zero, like the FPUT momenta that cancel to 1e-3,
// are compared on that scale, not in their own ulps) and the energy error to MAX_DIFF of
// the energy (as it is relative to it). Why 1e-14: a last-bit difference is 1.1e-16 of an
// O(1) entry; 100 steps of these non-chaotic chains amplify it a few times (measured:
// at most 1.1e-16, one last bit); 1e-14 leaves room and still catches any real difference in the numerics
// (a changed step or force is >= 1e-10 here). Exit status 1 on a larger difference; prints one line per run.
import { readFileSync } from "node:fs";
import { load } from "../physicskit.js";

const [wasmFile, nativeFile] = process.argv.slice(2);
const core = await load(readFileSync(wasmFile));
const native = readFileSync(nativeFile, "utf8").trim().split("\n").map((l) => JSON.parse(l));

// The same run as lab_reference.rs: FRAMES frames of STEPS steps of DT.
const FRAMES = 4, STEPS = 25, DT = 1e-3;
const bits = (x) => {
  const v = new DataView(new ArrayBuffer(8));
  v.setFloat64(0, x);
  return v.getBigUint64(0).toString(16).padStart(16, "0");
};

const MAX_DIFF = 1e-14;
const num = (hex) => new DataView(new BigUint64Array([BigInt(`0x${hex}`)]).buffer).getFloat64(0, true);
let failures = 0, identical = 0, close = 0, worst = 0;
for (const ref of native) {
  let got;
  try {
    const lab = core.build(ref.system, {});
    if (ref.tol !== undefined) lab.setTolerance(ref.tol);
    lab.setMethod(ref.method);
    for (let i = 0; i < FRAMES; i++) lab.step(STEPS, DT);
    got = { t: bits(lab.time()), energy_error: bits(lab.energyError()), state: Array.from(lab.state(), bits) };
    lab.free();
  } catch (e) {
    got = { error: String(e.message) };
  }
  let verdict;
  if (ref.error !== undefined || got.error !== undefined) {
    verdict = got.error === ref.error ? "same error" : "DIFFERENT";
  } else if (got.t === ref.t && got.energy_error === ref.energy_error &&
      JSON.stringify(got.state) === JSON.stringify(ref.state)) {
    verdict = "same bits";
  } else {
    const scale = Math.max(...ref.state.map((h) => Math.abs(num(h))));
    let d = Math.abs(num(got.t) - num(ref.t)) + Math.abs(num(got.energy_error) - num(ref.energy_error));
    got.state.forEach((g, i) => { d = Math.max(d, Math.abs(num(g) - num(ref.state[i])) / scale); });
    if (d > worst) worst = d;
    verdict = got.state.length === ref.state.length && d <= MAX_DIFF ? `within ${d.toExponential(1)}` : "DIFFERENT";
  }
  if (verdict === "same bits" || verdict === "same error") identical++;
  else if (verdict.startsWith("within")) close++;
  else failures++;
  console.log(`${verdict}  ${ref.system} ${ref.method}${ref.tol !== undefined ? ` tol ${ref.tol}` : ""}` +
    (verdict === "DIFFERENT" ? `\n  native ${JSON.stringify(ref)}\n  wasm   ${JSON.stringify(got)}` : ""));
}
console.log(`${identical} runs bit-identical, ${close} within ${worst.toExponential(1)} (libm), ${failures} different`);
process.exit(failures === 0 && native.length > 0 ? 0 : 1);
