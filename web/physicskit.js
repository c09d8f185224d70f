// The physicskit core in WebAssembly: a thin wrapper over the module's `pk_*` exports
// (crates/physicskit-wasm/src/exports.rs). Used by the page (lab.js) and by the Node test
// that compares it with the native build (test/node_compare.mjs).

const utf8 = new TextEncoder();
const fromUtf8 = new TextDecoder();

/** Loads the module from its bytes and returns the API. */
export async function load(bytes) {
  const { instance } = await WebAssembly.instantiate(bytes, {});
  return new Core(instance.exports);
}

class Core {
  constructor(x) {
    this.x = x;
  }
  f64(ptr, len) {
    // A fresh view each time: memory.buffer changes when the module's memory grows.
    return new Float64Array(this.x.memory.buffer, ptr, len);
  }
  text(ptr, len) {
    return fromUtf8.decode(new Uint8Array(this.x.memory.buffer, ptr, len));
  }
  error() {
    return this.text(this.x.pk_error_ptr(), this.x.pk_error_len());
  }
  putBytes(bytes) {
    const ptr = this.x.pk_input_bytes(bytes.length);
    new Uint8Array(this.x.memory.buffer, ptr, bytes.length).set(bytes);
  }
  putF64(values) {
    const ptr = this.x.pk_input_f64(values.length);
    this.f64(ptr, values.length).set(values);
  }
  check(status) {
    if (status !== 0) throw new Error(this.error());
  }
  /** The catalogue, as `physicskit list --json` prints it. */
  catalogue() {
    const len = this.x.pk_catalogue();
    return JSON.parse(this.text(this.x.pk_text_ptr(), len));
  }
  /** The input buffer holding `system`, `params` (as JSON) and `method`; their lengths. */
  putSetup(system, params, method) {
    const name = utf8.encode(system);
    const json = utf8.encode(JSON.stringify(params));
    const how = utf8.encode(method ?? "");
    const all = new Uint8Array(name.length + json.length + how.length);
    all.set(name);
    all.set(json, name.length);
    all.set(how, name.length + json.length);
    this.putBytes(all);
    return [name.length, json.length, how.length];
  }
  /**
   * The order the method `name` steps at on `system` with `params` (an object; missing names
   * take the defaults) and the tolerance `tol` (rtol = atol): Taylor's order is chosen by its
   * tolerance and the system's equations, every other method's is its catalogue order.
   */
  methodOrder(system, params, name, tol) {
    const order = this.x.pk_method_order(...this.putSetup(system, params, name), tol);
    if (order === 0) throw new Error(this.error());
    return order;
  }
  /**
   * Builds `system` with `params` (an object; missing names take the defaults) and the method
   * named `method` (null: the system's default), an adaptive one at the tolerance `tol`
   * (rtol = atol; null: the lab's default).
   */
  build(system, params = {}, method = null, tol = null) {
    const lengths = this.putSetup(system, params, method);
    const h = tol === null ? this.x.pk_build(...lengths) : this.x.pk_build_tol(...lengths, tol);
    if (h === 0) throw new Error(this.error());
    return new Lab(this, h);
  }
}

class Lab {
  constructor(core, h) {
    this.core = core;
    this.h = h;
  }
  free() {
    this.core.x.pk_free(this.h);
  }
  setMethod(name) {
    const bytes = utf8.encode(name);
    this.core.putBytes(bytes);
    this.core.check(this.core.x.pk_set_method(this.h, bytes.length));
  }
  /** Sets the tolerance (rtol = atol) of an adaptive method; a fixed-step one keeps it. */
  setTolerance(tol) {
    this.core.check(this.core.x.pk_set_tolerance(this.h, tol));
  }
  tolerance() {
    return this.core.x.pk_tolerance(this.h);
  }
  step(n, dt) {
    this.core.check(this.core.x.pk_step(this.h, n, dt));
  }
  /** A view of the current state (valid until the next call into the module). */
  state() {
    const x = this.core.x;
    return this.core.f64(x.pk_state_ptr(this.h), x.pk_state_len(this.h));
  }
  initialState() {
    const x = this.core.x;
    return this.core.f64(x.pk_initial_ptr(this.h), x.pk_state_len(this.h));
  }
  positions() {
    const x = this.core.x;
    return this.core.f64(x.pk_positions_ptr(this.h), x.pk_positions_len(this.h));
  }
  /** Drawing positions of the configuration `q` (an array), or an empty array. */
  positionsOf(q) {
    this.core.putF64(q);
    const n = this.core.x.pk_positions_of(this.h, q.length);
    if (n < 0) throw new Error(this.core.error());
    return Array.from(this.core.f64(this.core.x.pk_probe_ptr(this.h), n));
  }
  crossings() {
    const x = this.core.x;
    return this.core.f64(x.pk_crossings_ptr(this.h), x.pk_crossings_len(this.h));
  }
  /** The orbit number of each crossing (equal numbers: one orbit). */
  crossingOrbits() {
    const x = this.core.x;
    return new Uint32Array(x.memory.buffer, x.pk_crossing_orbits_ptr(this.h), x.pk_crossing_orbits_len(this.h));
  }
  /** The energy of any state of this system. */
  energyOf(values) {
    this.core.putF64(values);
    const e = this.core.x.pk_energy_of(this.h, values.length);
    if (Number.isNaN(e)) throw new Error(this.core.error());
    return e;
  }
  time() {
    return this.core.x.pk_time(this.h);
  }
  energy() {
    return this.core.x.pk_energy(this.h);
  }
  energy0() {
    return this.core.x.pk_energy0(this.h);
  }
  energyError() {
    return this.core.x.pk_energy_error(this.h);
  }
  setState(values) {
    this.core.putF64(values);
    this.core.check(this.core.x.pk_set_state(this.h, values.length));
  }
  reset() {
    this.core.check(this.core.x.pk_reset(this.h));
  }
  setSection(k, value, direction) {
    this.core.check(this.core.x.pk_set_section(this.h, k, value, direction));
  }
  clearCrossings() {
    this.core.check(this.core.x.pk_clear_crossings(this.h));
  }
  /** New run at the current energy: `assign` is [[index, value], ...], `solve` the momentum. */
  launch(assign, solve) {
    this.core.putF64(assign.flat());
    this.core.check(this.core.x.pk_launch(this.h, assign.length, solve));
  }
}
