//! A [`Tape`]'s `f64` evaluation compiled to machine code by Cranelift (feature `jit`, native
//! targets only).
//!
//! One function per tape, `fn(first, second, t, out) -> last`: it loads the inputs it uses,
//! runs the operations in tape order as SSA values (Cranelift allocates the registers, so
//! nothing is zeroed or copied), stores every output but the last into `out` and returns the
//! last. Each operation is the interpreter's: `+ - * /`, negation, `|x|` and `sqrt` are the
//! IEEE operations (correctly rounded, so the bits of Rust's), squares a multiplication, and
//! every other power and function a call of an `extern "C"` shim that runs the interpreter's
//! own [`Op::apply`] (`powi` with its exponent as a run-time argument, as the interpreter
//! has it). Cranelift does not contract a multiplication and an addition into a fused
//! multiply-add unless asked to (it never is here), so the results are the interpreter's bit
//! for bit (`tests/classical/lagrangian/jit.rs` checks every operation and whole runs).
//!
//! A tape is compiled lazily, by the evaluation that comes after [`COMPILE_AFTER`]
//! interpreted ones: a tape evaluated a few times (a kinetic energy at rest, a parameter
//! sweep's short runs) never pays the compilation, and since both give the same bits a run
//! does not notice the switch. If compilation fails (a host
//! Cranelift does not support) the tape stays interpreted. The code lives in a
//! [`JITModule`] shared by a tape's clones behind an `Arc` and freed with the last of them.

use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::{Arc, Mutex, OnceLock};

use cranelift_codegen::ir::{types, AbiParam, InstBuilder, MemFlags, SigRef, Signature, Value};
use cranelift_codegen::isa::{self, CallConv};
use cranelift_codegen::settings::{self, Configurable};
use cranelift_frontend::{FunctionBuilder, FunctionBuilderContext};
use cranelift_jit::{JITBuilder, JITModule};
use cranelift_module::{default_libcall_names, Linkage, Module};

use super::{Func, Op, Out, Tape, Val, COMPILE_AFTER};

/// The compiled function: `first`, `second`, `t`, `out`; returns the last output.
type Entry = unsafe extern "C" fn(*const f64, *const f64, f64, *mut f64) -> f64;

/// A tape's native code, or its absence, shared by the tape's clones.
#[derive(Clone, Default)]
pub(super) struct Jit(Arc<State>);

#[derive(Default)]
struct State {
    evaluations: AtomicU32,
    code: OnceLock<Option<Native>>,
}

impl std::fmt::Debug for Jit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let state = match self.0.code.get() {
            Some(Some(_)) => "native",
            Some(None) => "interpreted (compilation failed)",
            None => "interpreted",
        };
        f.write_str(state)
    }
}

/// The code is a function of the tape's operations, which the tape's equality compares.
impl PartialEq for Jit {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

impl Jit {
    /// The native code, compiling it on the [`COMPILE_AFTER`]-th call.
    #[inline]
    pub(super) fn code(&self, tape: &Tape) -> Option<&Native> {
        if let Some(code) = self.0.code.get() {
            return code.as_ref();
        }
        if self.0.evaluations.fetch_add(1, Ordering::Relaxed) < COMPILE_AFTER {
            return None;
        }
        self.compile(tape)
    }

    /// Compiles now (once; later calls return the first outcome).
    pub(super) fn compile(&self, tape: &Tape) -> Option<&Native> {
        let host = || cranelift_native::builder().map_err(str::to_owned);
        self.0
            .code
            .get_or_init(|| Native::compile(tape, host()))
            .as_ref()
    }

    /// Compiles for an architecture this build of Cranelift does not generate code for, the
    /// failure a host Cranelift does not support meets: the tape stays interpreted.
    pub(super) fn compile_for_foreign_target(&self, tape: &Tape) -> Option<&Native> {
        let foreign = if cfg!(target_arch = "s390x") {
            "x86_64-unknown-linux-gnu"
        } else {
            "s390x-unknown-linux-gnu"
        };
        let isa = isa::lookup_by_name(foreign).map_err(|e| e.to_string());
        self.0
            .code
            .get_or_init(|| Native::compile(tape, isa))
            .as_ref()
    }

    /// Whether native code runs the evaluations.
    pub(super) fn is_native(&self) -> bool {
        matches!(self.0.code.get(), Some(Some(_)))
    }
}

/// A compiled tape: its entry point and the module that owns the code.
pub(super) struct Native {
    entry: Entry,
    n_first: usize,
    n_second: usize,
    n_outputs: usize,
    /// Owns the code `entry` points into.
    _module: OwnedModule,
}

/// A [`JITModule`] whose code is freed when this is dropped: the owner of a compiled
/// function (a tape's, or a Taylor program's in `taylor_jit.rs`) holds it beside the entry
/// point, so the code outlives every call.
pub(in crate::classical::symbolic) struct OwnedModule(
    /// `Some` until dropped. A `Mutex` only to make the (`Send`, not `Sync`) module `Sync`;
    /// it is locked by nobody but `drop`.
    Mutex<Option<JITModule>>,
);

impl OwnedModule {
    pub(in crate::classical::symbolic) fn new(module: JITModule) -> Self {
        Self(Mutex::new(Some(module)))
    }
}

impl Drop for OwnedModule {
    // SAFETY: `free_memory` unmaps the code; its owner's entry point is reachable only through
    // `&owner`, so no call can run or follow once the owner is being dropped.
    #[allow(unsafe_code)]
    fn drop(&mut self) {
        let module = match self.0.get_mut() {
            Ok(module) => module.take(),
            Err(poisoned) => poisoned.into_inner().take(),
        };
        if let Some(module) = module {
            unsafe { module.free_memory() }
        }
    }
}

/// The code generator's settings for code called through a pointer from anywhere in the
/// address space, optimized for speed.
pub(in crate::classical::symbolic) fn flag_builder() -> Option<settings::Builder> {
    let mut flags = settings::builder();
    flags.set("is_pic", "false").ok()?;
    flags.set("use_colocated_libcalls", "false").ok()?;
    flags.set("opt_level", "speed").ok()?;
    Some(flags)
}

impl Native {
    /// Runs the code on `first`, `second` (at least the tape's lengths), `t`, writing outputs
    /// `0..n - 1` into `out` (at least `n - 1` long) and returning output `n - 1`; `NaN` for
    /// slices too short (callers check them first).
    #[inline]
    // SAFETY: the code reads `first[..n_first]` and `second[..n_second]` and writes
    // `out[..n_outputs - 1]`, which the check makes in bounds; it touches no other memory and
    // calls only the shims below, which are plain functions of their arguments.
    #[allow(unsafe_code)]
    pub(super) fn call(&self, first: &[f64], second: &[f64], t: f64, out: &mut [f64]) -> f64 {
        if first.len() < self.n_first
            || second.len() < self.n_second
            || out.len() + 1 < self.n_outputs
        {
            return f64::NAN;
        }
        unsafe { (self.entry)(first.as_ptr(), second.as_ptr(), t, out.as_mut_ptr()) }
    }

    fn compile(tape: &Tape, isa: Result<isa::Builder, String>) -> Option<Native> {
        if tape.outputs.is_empty() {
            return None;
        }
        let params = [Param::Pointer, Param::Pointer, Param::F64, Param::Pointer];
        let (code, module) = compile_function(
            isa.ok()?,
            flag_builder()?,
            &params,
            true,
            |b, params, shims| {
                let mut emit = Emitter::new(b, shims, tape, params);
                for op in &tape.ops {
                    let v = emit.op(*op);
                    emit.slots.push(Some(v));
                }
                vec![emit.outputs(&tape.outputs, params[3])]
            },
        )?;
        Some(Native {
            entry: entry_point(code),
            n_first: tape.n_first,
            n_second: tape.n_second,
            n_outputs: tape.outputs.len(),
            _module: module,
        })
    }
}

/// A parameter of a generated function.
#[derive(Clone, Copy)]
pub(in crate::classical::symbolic) enum Param {
    /// A pointer (to `f64`s).
    Pointer,
    F64,
}

/// Compiles one function for the target `isa` with `flags`: parameters `params`, an `f64`
/// result if `returns`, and a single block whose instructions `body` emits from the
/// parameters' values, returning the values the function returns. The finalized code, and
/// the module that owns it; `None` where Cranelift fails or the target's pointers are not
/// 64-bit.
pub(in crate::classical::symbolic) fn compile_function(
    isa: isa::Builder,
    flags: settings::Builder,
    params: &[Param],
    returns: bool,
    body: impl FnOnce(&mut FunctionBuilder<'_>, &[Value], &mut Shims) -> Vec<Value>,
) -> Option<(*const u8, OwnedModule)> {
    let isa = isa.finish(settings::Flags::new(flags)).ok()?;
    if isa.pointer_bytes() != 8 {
        return None;
    }
    let call_conv = isa.default_call_conv();
    let mut module = JITModule::new(JITBuilder::with_isa(isa, default_libcall_names()));
    let pointer = module.target_config().pointer_type();
    let mut signature = module.make_signature();
    for param in params {
        let ty = match param {
            Param::Pointer => pointer,
            Param::F64 => types::F64,
        };
        signature.params.push(AbiParam::new(ty));
    }
    if returns {
        signature.returns.push(AbiParam::new(types::F64));
    }
    let id = module
        .declare_function("generated", Linkage::Local, &signature)
        .ok()?;
    let mut context = module.make_context();
    context.func.signature = signature;
    let mut builder_context = FunctionBuilderContext::new();
    {
        let mut b = FunctionBuilder::new(&mut context.func, &mut builder_context);
        let block = b.create_block();
        b.append_block_params_for_function_params(block);
        b.switch_to_block(block);
        b.seal_block(block);
        let values = b.block_params(block).to_vec();
        let mut shims = Shims {
            pointer,
            call_conv,
            signatures: Vec::new(),
        };
        let results = body(&mut b, &values, &mut shims);
        b.ins().return_(&results);
        b.finalize();
    }
    module.define_function(id, &mut context).ok()?;
    module.clear_context(&mut context);
    module.finalize_definitions().ok()?;
    let code = module.get_finalized_function(id);
    Some((code, OwnedModule::new(module)))
}

/// Machine code written elsewhere (`taylor_asm.rs`: position-independent, calling only
/// absolute addresses) mapped executable by a [`JITModule`] for this host: its address, and the
/// module that owns it; `None` where the host has no ISA Cranelift knows or mapping fails.
pub(in crate::classical::symbolic) fn load_code(bytes: &[u8]) -> Option<(*const u8, OwnedModule)> {
    let isa = cranelift_native::builder()
        .ok()?
        .finish(settings::Flags::new(flag_builder()?))
        .ok()?;
    let mut module = JITModule::new(JITBuilder::with_isa(isa, default_libcall_names()));
    let signature = module.make_signature();
    let id = module
        .declare_function("written", Linkage::Local, &signature)
        .ok()?;
    module.define_function_bytes(id, 64, bytes, &[]).ok()?;
    module.finalize_definitions().ok()?;
    let code = module.get_finalized_function(id);
    Some((code, OwnedModule::new(module)))
}

/// Calls of `extern "C"` shims (plain Rust functions of `f64` and `i32` arguments returning an
/// `f64`) from generated code, each signature imported once.
pub(in crate::classical::symbolic) struct Shims {
    pointer: types::Type,
    call_conv: CallConv,
    signatures: Vec<(Vec<types::Type>, SigRef)>,
}

impl Shims {
    /// A call of the shim at `address` on `args` (its parameters' types are theirs).
    pub(in crate::classical::symbolic) fn call(
        &mut self,
        b: &mut FunctionBuilder<'_>,
        address: usize,
        args: &[Value],
    ) -> Value {
        let kinds: Vec<types::Type> = args.iter().map(|&v| b.func.dfg.value_type(v)).collect();
        let sig = match self.signatures.iter().find(|(k, _)| *k == kinds) {
            Some(&(_, sig)) => sig,
            None => {
                let mut s = Signature::new(self.call_conv);
                for &ty in &kinds {
                    s.params.push(AbiParam::new(ty));
                }
                s.returns.push(AbiParam::new(types::F64));
                let sig = b.import_signature(s);
                self.signatures.push((kinds, sig));
                sig
            }
        };
        let callee = b.ins().iconst(self.pointer, address as i64);
        let call = b.ins().call_indirect(sig, callee, args);
        b.inst_results(call)[0]
    }
}

/// The compiled function's pointer as its type.
// SAFETY: `code` is the finalized code of a function declared with `Entry`'s signature in the
// platform's default calling convention, which is `extern "C"`'s.
#[allow(unsafe_code)]
fn entry_point(code: *const u8) -> Entry {
    unsafe { std::mem::transmute::<*const u8, Entry>(code) }
}

/// `powi` as the interpreter runs it (exponent a run-time value).
extern "C" fn powi(x: f64, n: i32) -> f64 {
    Op::Powi(0, n).apply(&[x], 0)
}

/// `powf` as the interpreter runs it.
extern "C" fn powf(x: f64, y: f64) -> f64 {
    Op::Powf(0, y).apply(&[x], 0)
}

/// `x^y` for a run-time `y`, as the interpreter runs it.
extern "C" fn pow(x: f64, y: f64) -> f64 {
    Op::Pow(0, 1).apply(&[x, y], 1)
}

/// `Func::ALL[F]` as the interpreter runs it.
extern "C" fn func<const F: usize>(x: f64) -> f64 {
    Func::ALL[F].apply(x)
}

/// The shims of [`Func::ALL`], in its order.
const FUNCS: [extern "C" fn(f64) -> f64; 13] = [
    func::<0>, func::<1>, func::<2>, func::<3>, func::<4>, func::<5>, func::<6>, func::<7>,
    func::<8>, func::<9>, func::<10>, func::<11>, func::<12>,
];

/// Emits a tape's operations into one block.
struct Emitter<'a, 'b> {
    b: &'a mut FunctionBuilder<'b>,
    shims: &'a mut Shims,
    tape: &'a Tape,
    params: &'a [Value],
    /// A value per slot: inputs loaded on first use, then one per operation.
    slots: Vec<Option<Value>>,
}

impl<'a, 'b> Emitter<'a, 'b> {
    fn new(
        b: &'a mut FunctionBuilder<'b>,
        shims: &'a mut Shims,
        tape: &'a Tape,
        params: &'a [Value],
    ) -> Self {
        Self {
            b,
            shims,
            tape,
            params,
            slots: vec![None; tape.n_inputs()],
        }
    }

    fn slot(&mut self, s: u32) -> Value {
        let s = s as usize;
        if let Some(v) = self.slots[s] {
            return v;
        }
        let (nf, ns) = (self.tape.n_first, self.tape.n_second);
        let v = if s < nf + ns {
            let (base, i) = if s < nf {
                (self.params[0], s)
            } else {
                (self.params[1], s - nf)
            };
            // In bounds and aligned: `Native::call` checks the lengths of `f64` slices.
            self.b
                .ins()
                .load(types::F64, MemFlags::trusted(), base, (8 * i) as i32)
        } else {
            self.params[2]
        };
        self.slots[s] = Some(v);
        v
    }

    fn c(&mut self, c: f64) -> Value {
        self.b.ins().f64const(c)
    }

    fn call(&mut self, address: usize, args: &[Value]) -> Value {
        self.shims.call(self.b, address, args)
    }

    /// The operation, on operands in the order [`Op::apply`] has them.
    fn op(&mut self, op: Op) -> Value {
        let (x, y) = match op {
            Op::Add(a, b) | Op::Sub(a, b) | Op::Mul(a, b) | Op::Div(a, b) | Op::Pow(a, b) => {
                (self.slot(a), Some(self.slot(b)))
            }
            Op::AddC(a, c)
            | Op::MulC(a, c)
            | Op::SubC(a, c)
            | Op::DivC(a, c)
            | Op::PowC(a, c)
            | Op::Powf(a, c) => (self.slot(a), Some(self.c(c))),
            Op::CSub(c, a) | Op::CDiv(c, a) | Op::CPow(c, a) => (self.c(c), Some(self.slot(a))),
            Op::Powi(a, n) => {
                let a = self.slot(a);
                (a, Some(self.b.ins().iconst(types::I32, i64::from(n))))
            }
            Op::Neg(a) | Op::Square(a) | Op::Func(_, a) => (self.slot(a), None),
        };
        // Unary operations: `Square` is `x * x`, the others ignore `y`.
        let y = y.unwrap_or(x);
        match op {
            Op::Add(..) | Op::AddC(..) => self.b.ins().fadd(x, y),
            Op::Sub(..) | Op::SubC(..) | Op::CSub(..) => self.b.ins().fsub(x, y),
            Op::Mul(..) | Op::MulC(..) | Op::Square(_) => self.b.ins().fmul(x, y),
            Op::Div(..) | Op::DivC(..) | Op::CDiv(..) => self.b.ins().fdiv(x, y),
            Op::Neg(_) => self.b.ins().fneg(x),
            Op::Powi(..) => self.call(powi as *const () as usize, &[x, y]),
            Op::Powf(..) => self.call(powf as *const () as usize, &[x, y]),
            Op::Pow(..) | Op::PowC(..) | Op::CPow(..) => {
                self.call(pow as *const () as usize, &[x, y])
            }
            Op::Func(Func::Sqrt, _) => self.b.ins().sqrt(x),
            Op::Func(Func::Abs, _) => self.b.ins().fabs(x),
            Op::Func(f, _) => self.call(FUNCS[f as usize] as usize, &[x]),
        }
    }

    /// Stores outputs `0..n - 1` at `out` and returns output `n - 1`.
    fn outputs(&mut self, outputs: &[Out], out: Value) -> Value {
        let mut last = None;
        for (i, &Out(v, negate)) in outputs.iter().enumerate() {
            let mut v = match v {
                Val::Slot(s) => self.slot(s),
                Val::Const(c) => self.c(c),
            };
            if negate {
                v = self.b.ins().fneg(v);
            }
            if i + 1 == outputs.len() {
                last = Some(v);
            } else {
                self.b
                    .ins()
                    .store(MemFlags::trusted(), v, out, (8 * i) as i32);
            }
        }
        last.unwrap_or_else(|| self.c(f64::NAN))
    }
}
