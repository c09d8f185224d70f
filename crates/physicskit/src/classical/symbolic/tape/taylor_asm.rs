//! A [`TaylorProgram`](super::super::TaylorProgram)'s recurrences, for one state or for
//! [`TaylorLanes`](super::super::TaylorLanes), as x86-64 AVX machine code written directly
//! (x86-64 hosts with AVX, System V calling convention): what `taylor_jit.rs` (its unrolled
//! form, [`Form::Avx`](super::Form::Avx)) and `taylor_lanes_jit.rs` make first, before
//! Cranelift, whose x86-64 backend has no vectors wider than 128 bits, folds few loads into
//! the arithmetic, and takes ten times as long to compile this code.
//!
//! The code is the unrolled form (`taylor_jit.rs`'s [`Recurrences`], emitted by the same
//! provided methods in the same order) on the scalar instructions of an `xmm` (one state) or
//! on whole `ymm` (4 lanes) or `zmm` (8 lanes, AVX-512F) registers: one pass of it covers
//! [`width`] lanes, and a loop runs it over the `L` lanes. One state's code also stores each
//! of the state's coefficients into the stepper's blocks at the end of the work array
//! (`taylor_tape.rs`'s `WorkLayout`), so that the stepper copies them rather than transposing
//! the rows.
//! It is made in three steps:
//! 1. **record**: the [`Recurrences`] calls become a list of [`Op`]s on values numbered by
//!    the op that made them (a coefficient of the order being computed used as the value
//!    just computed, older ones loaded, as in the other emitters);
//! 2. **allocate**: one walk over the list assigns registers from each value's last use and
//!    writes the machine instructions ([`Inst`]). A load is not an instruction of its own
//!    but an operand read from memory by the arithmetic that uses it (x86's folded loads),
//!    and so is a constant (read from a pool after the code). When the registers run out, the
//!    value used last is dropped from its register: for free if it is already in memory (a
//!    stored coefficient, a load, a constant), else stored to a stack slot;
//! 3. **encode**: [`iced_x86`]'s assembler turns the instructions into bytes, which
//!    Cranelift's JIT module maps executable ([`load_code`]).
//!
//! Addition, subtraction, multiplication, division and square root are the IEEE operations
//! lane by lane, negation flips the sign bit (as Cranelift's `fneg` does), nothing is fused
//! into a multiply-add, and an addition or a multiplication may take its operands in either
//! order (IEEE addition and multiplication commute exactly): each lane does the interpreter's
//! operations in its order and gets its bits. Order 0 of the transcendental operations calls
//! the scalar JIT's `extern "C"` shims lane by lane (every register saved first: the calling
//! convention keeps none of them). One state's code on an AVX2 host sums the groups of four
//! terms of a long Cauchy or weighted sum (`taylor_tape.rs`'s `ordered_sum`) as whole `ymm`
//! vectors: each group's four terms in the lanes, the reversed factor read by `vpermpd`, then
//! the lanes added in the order the partial sums are ([`Groups`]). Order `k` of `|a|`, `-a_k`
//! where `a_0 < 0` and else `a_k`, is `a_k` with its sign bit flipped by the sign bit of
//! `min(a_0, +0)`: x86's minimum gives its second operand, `+0`, for a NaN and for `-0`, so
//! only an `a_0` below zero sets it (no branch, in every lane).
//! `tests/classical/integrators/taylor_jit.rs` and
//! `taylor_lanes.rs` check this code and Cranelift's against the interpreter on every
//! recurrence at orders 1–24 (one state; 4, 8 and 16 lanes), and the unit test below with
//! one to five registers, so that the allocator spills.

use iced_x86::code_asm::{
    ptr, qword_ptr, r12, rax, rbx, rdi, registers, rsp, AsmMemoryOperand, AsmRegisterXmm,
    AsmRegisterYmm, AsmRegisterZmm, CodeAssembler, CodeLabel, IcedError,
};

use super::super::{Node, Val, Weight, WorkLayout};
use super::{powf, Fresh, Recurrences};
use crate::classical::symbolic::tape::jit::{load_code, OwnedModule};

/// Lanes per register for `lanes` lanes on this host: 1 (an `xmm`'s low double) for one
/// state with AVX, 8 (`zmm`) with AVX-512F where `lanes` is a multiple of 8, 4 (`ymm`) with
/// AVX where it is a multiple of 4; `None` otherwise (this code is then not made).
pub(in crate::classical::symbolic) fn width(lanes: usize) -> Option<usize> {
    if lanes == 1 && std::arch::is_x86_feature_detected!("avx") {
        Some(1)
    } else if lanes.is_multiple_of(8) && std::arch::is_x86_feature_detected!("avx512f") {
        Some(8)
    } else if lanes.is_multiple_of(4) && std::arch::is_x86_feature_detected!("avx") {
        Some(4)
    } else {
        None
    }
}

/// The recurrences of `order` for `lanes` lanes as machine code, its entry point
/// (`extern "C" fn(*mut f64)` on the lanes' work array) and the module owning it; `None`
/// where the host lacks AVX or the program's offsets do not fit the encoding.
pub(in crate::classical::symbolic) fn compile(
    nodes: &[Node],
    outputs: &[Val],
    lanes: usize,
    order: usize,
) -> Option<(*const u8, OwnedModule)> {
    compile_on(nodes, outputs, lanes, None, order, None)
}

/// [`compile`] for one state on the work array of `layout`, each of the state's coefficients
/// also stored into its blocks.
pub(in crate::classical::symbolic) fn compile_scalar(
    nodes: &[Node],
    outputs: &[Val],
    layout: WorkLayout,
    order: usize,
) -> Option<(*const u8, OwnedModule)> {
    compile_on(nodes, outputs, 1, Some(layout), order, None)
}

/// [`compile`] (with the blocks of `layout` written, if given, for one lane) on at most
/// `registers` vector registers (all of them if `None`): tests take few to make the allocator
/// spill.
fn compile_on(
    nodes: &[Node],
    outputs: &[Val],
    lanes: usize,
    layout: Option<WorkLayout>,
    order: usize,
    registers: Option<usize>,
) -> Option<(*const u8, OwnedModule)> {
    let width = width(lanes)?;
    let layout = layout.filter(|_| lanes == 1);
    let all = if width == 8 { 32 } else { 16 };
    let registers = registers.map_or(all, |r| r.clamp(1, all));
    // A group's sum takes two registers of its own.
    let groups = width == 1 && registers >= 2 && std::arch::is_x86_feature_detected!("avx2");
    let mut recorder = Recorder::of(nodes, outputs, order, layout, groups);
    let sign = recorder.constant(-0.0);
    let (code, slots) = allocate(&recorder.ops, registers, sign);
    let frame = Frame {
        lanes,
        width,
        slots,
    };
    let bytes = frame
        .encode(&code, &recorder.pool, &recorder.weights)
        .ok()?;
    load_code(&bytes)
}

/// An operation of the recorded recurrences; its value (if any) is numbered by its place in
/// the list.
#[derive(Clone, Copy)]
enum Op {
    /// Coefficient `i` of the work array (`node × (order + 1) + j`).
    Load(usize),
    /// Constant `i` of the pool.
    Constant(usize),
    Arith(Arith, usize, usize),
    Neg(usize),
    Sqrt(usize),
    /// The shim at `address` lane by lane on value `x`, with the pool's constant `alpha` as
    /// second argument if given.
    Call {
        address: usize,
        x: usize,
        alpha: Option<usize>,
    },
    /// Value `x` stored to coefficient `i`.
    Store(usize, usize),
    /// The groups of a Cauchy or weighted sum.
    Groups(Groups),
}

/// The groups of a Cauchy or weighted sum (a power's, an exponential's or a sine–cosine
/// pair's; one state; `taylor_tape.rs`'s `ordered_sum`): `(p_0 + p_2) + (p_1 + p_3)` of the
/// four lanes' sums `p_l = Σ_g t_{4g+l}`, `g` below `groups`, of the terms
/// `t_i = (w_i · rev_i) · fwd_i` (`i` counted from the first grouped term; no `w_i` without
/// weights): `fwd_i` is coefficient `fwd + i` of the work array, `rev_i` coefficient `rev - i`,
/// and `w_i` lane `i mod 4` of entry `weights + i / 4` of [`Recorder::weights`].
#[derive(Clone, Copy)]
struct Groups {
    fwd: usize,
    rev: usize,
    groups: usize,
    weights: Option<usize>,
}

#[derive(Clone, Copy, PartialEq)]
enum Arith {
    Add,
    Sub,
    Mul,
    Div,
    /// x86's minimum: the first operand where it is below the second, else the second (for
    /// equal zeros and for a NaN in either).
    Min,
    /// Bitwise and, on the doubles' bits.
    And,
    /// Bitwise exclusive or, on the doubles' bits.
    Xor,
}

/// Records the [`Recurrences`] calls as [`Op`]s.
struct Recorder {
    ops: Vec<Op>,
    pool: Vec<f64>,
    fresh: Fresh<usize>,
    /// Where the state's coefficients are stored a second time, if they are.
    blocks: Option<WorkLayout>,
    /// Whether the sums' groups are summed as [`Groups`] (one state, AVX2: `vpermpd`).
    groups: bool,
    /// The weights of the [`Groups`], four to an entry.
    weights: Vec<[f64; 4]>,
}

impl Recorder {
    /// The recurrences of `order` recorded (each of the state's coefficients stored into the
    /// blocks of `blocks` too, if given; the sums' groups as vectors if `groups`).
    fn of(
        nodes: &[Node],
        outputs: &[Val],
        order: usize,
        blocks: Option<WorkLayout>,
        groups: bool,
    ) -> Self {
        let mut recorder = Recorder {
            ops: Vec::new(),
            pool: Vec::new(),
            fresh: Fresh::new(WorkLayout::new(nodes, outputs.len(), order)),
            blocks,
            groups,
            weights: Vec::new(),
        };
        if let Some(blocks) = blocks {
            for i in 0..blocks.dim {
                let y = recorder.ld(i, 0);
                recorder.push(Op::Store(blocks.in_blocks(i, 0), y));
            }
        }
        recorder.recurrences(nodes, outputs, order);
        recorder
    }

    fn push(&mut self, op: Op) -> usize {
        self.ops.push(op);
        self.ops.len() - 1
    }

    /// The pool's index of `c` (bit for bit), added if new.
    fn constant(&mut self, c: f64) -> usize {
        let bits = c.to_bits();
        if let Some(i) = self.pool.iter().position(|p| p.to_bits() == bits) {
            return i;
        }
        self.pool.push(c);
        self.pool.len() - 1
    }
}

impl Recurrences for Recorder {
    type X = usize;

    fn set_k(&mut self, k: usize) {
        self.fresh.set_k(k);
    }

    fn lead(&self) -> usize {
        self.fresh.lead()
    }

    fn ld(&mut self, n: usize, j: usize) -> usize {
        match self.fresh.get(n, j) {
            Some(v) => v,
            None => self.push(Op::Load(self.fresh.index(n, j))),
        }
    }

    fn st(&mut self, n: usize, j: usize, x: usize) {
        self.fresh.set(n, j, x);
        self.push(Op::Store(self.fresh.index(n, j), x));
        // Only the state's coefficients are stored from the outputs (`st(i, k + 1, ...)`),
        // the state's rows being the first nodes.
        if let Some(blocks) = self.blocks.filter(|b| n < b.dim) {
            self.push(Op::Store(blocks.in_blocks(n, j), x));
        }
    }

    fn c(&mut self, c: f64) -> usize {
        let i = self.constant(c);
        self.push(Op::Constant(i))
    }

    fn add(&mut self, x: usize, y: usize) -> usize {
        self.push(Op::Arith(Arith::Add, x, y))
    }

    fn sub(&mut self, x: usize, y: usize) -> usize {
        self.push(Op::Arith(Arith::Sub, x, y))
    }

    fn mul(&mut self, x: usize, y: usize) -> usize {
        self.push(Op::Arith(Arith::Mul, x, y))
    }

    fn div(&mut self, x: usize, y: usize) -> usize {
        self.push(Op::Arith(Arith::Div, x, y))
    }

    fn neg(&mut self, x: usize) -> usize {
        self.push(Op::Neg(x))
    }

    fn sqrt(&mut self, x: usize) -> usize {
        self.push(Op::Sqrt(x))
    }

    /// `x` with its sign bit flipped by `min(x0, +0)`'s (see the module documentation).
    fn abs(&mut self, x0: usize, x: usize) -> usize {
        let zero = self.c(0.0);
        let below = self.push(Op::Arith(Arith::Min, x0, zero));
        let sign = self.c(-0.0);
        let flip = self.push(Op::Arith(Arith::And, below, sign));
        self.push(Op::Arith(Arith::Xor, flip, x))
    }

    fn call(&mut self, address: usize, x: usize) -> usize {
        self.push(Op::Call {
            address,
            x,
            alpha: None,
        })
    }

    fn cauchy_groups(
        &mut self,
        (a, a1): (usize, usize),
        (b, b1): (usize, usize),
        groups: usize,
    ) -> Option<usize> {
        self.groups.then(|| {
            self.push(Op::Groups(Groups {
                fwd: self.fresh.index(a, a1),
                rev: self.fresh.index(b, b1),
                groups,
                weights: None,
            }))
        })
    }

    fn weighted_groups(
        &mut self,
        a: usize,
        (b, b0): (usize, usize),
        k: usize,
        weight: Weight,
        groups: usize,
    ) -> Option<usize> {
        if !self.groups {
            return None;
        }
        let first = self.weights.len();
        let lead = self.lead();
        for g in 0..groups {
            let w = std::array::from_fn(|l| weight.at(k, lead + 4 * g + l));
            self.weights.push(w);
        }
        Some(self.push(Op::Groups(Groups {
            fwd: self.fresh.index(b, b0 + lead),
            rev: self.fresh.index(a, k - lead),
            groups,
            weights: Some(first),
        })))
    }

    fn powf(&mut self, x: usize, alpha: f64) -> usize {
        let alpha = Some(self.constant(alpha));
        self.push(Op::Call {
            address: powf as *const () as usize,
            x,
            alpha,
        })
    }
}

/// Where a value is: a vector register, or memory an instruction can read it from.
#[derive(Clone, Copy, PartialEq)]
enum Loc {
    Reg(u8),
    /// Coefficient `i` of the work array, at this pass's lanes.
    Work(usize),
    /// Stack slot `i`.
    Slot(usize),
    /// Constant `i` of the pool (the same in every lane).
    Pool(usize),
}

/// A machine instruction on whole vectors.
enum Inst {
    Load {
        dst: u8,
        src: Loc,
    },
    Store {
        dst: Loc,
        src: u8,
    },
    Arith {
        op: Arith,
        dst: u8,
        a: u8,
        b: Loc,
    },
    Sqrt {
        dst: u8,
        x: Loc,
    },
    /// `a` with the sign bits of the pool's constant `mask` flipped.
    Xor {
        dst: u8,
        a: u8,
        mask: usize,
    },
    /// [`Groups`] summed into `dst`, through `acc` and `tmp` (`ymm`; `dst` may be either).
    Groups {
        dst: u8,
        acc: u8,
        tmp: u8,
        sum: Groups,
    },
    /// The shim at `address` lane by lane on `x` (in memory), results to stack slot `out`.
    Call {
        address: usize,
        x: Loc,
        alpha: Option<usize>,
        out: usize,
    },
}

/// The register allocator's state: every value's place, every register's value.
struct Allocator {
    code: Vec<Inst>,
    loc: Vec<Loc>,
    /// A copy of the value in memory, once it has one (its load, constant, store or slot).
    home: Vec<Option<Loc>>,
    /// The last op reading each value (`None` if none does).
    last: Vec<Option<usize>>,
    /// Each register's value (`usize::MAX` for a scratch use), `None` if free.
    owner: Vec<Option<usize>>,
    /// Stack slots in all.
    slots: usize,
    /// Slots whose value has been read for the last time, free for later values.
    free_slots: Vec<usize>,
    /// Slots whose value the op being allocated reads for the last time: free once its
    /// instruction is written (a spill before it must not overwrite them).
    freed: Vec<usize>,
}

/// The instructions of `ops` on `registers` vector registers, and the stack slots they use;
/// `sign` is the pool's `-0.0`, whose bits negate.
fn allocate(ops: &[Op], registers: usize, sign: usize) -> (Vec<Inst>, usize) {
    let mut last = vec![None; ops.len()];
    for (i, op) in ops.iter().enumerate() {
        let mut read = |v: usize| last[v] = Some(i);
        match *op {
            Op::Arith(_, x, y) => {
                read(x);
                read(y);
            }
            Op::Neg(x) | Op::Sqrt(x) | Op::Call { x, .. } | Op::Store(_, x) => read(x),
            Op::Load(_) | Op::Constant(_) | Op::Groups(_) => {}
        }
    }
    let mut a = Allocator {
        code: Vec::new(),
        loc: vec![Loc::Pool(0); ops.len()],
        home: vec![None; ops.len()],
        last,
        owner: vec![None; registers],
        slots: 0,
        free_slots: Vec::new(),
        freed: Vec::new(),
    };
    for (i, op) in ops.iter().enumerate() {
        match *op {
            Op::Load(c) => a.place_in_memory(i, Loc::Work(c)),
            Op::Constant(p) => a.place_in_memory(i, Loc::Pool(p)),
            Op::Arith(op, x, y) => {
                let in_reg = |v: usize| matches!(a.loc[v], Loc::Reg(_));
                // x86's minimum does not commute (for zeros and NaNs).
                let commutes = matches!(op, Arith::Add | Arith::Mul | Arith::And | Arith::Xor);
                let (x, y) = if commutes && !in_reg(x) && in_reg(y) {
                    (y, x)
                } else {
                    (x, y)
                };
                let xr = a.in_register(x);
                let yl = a.loc[y];
                a.release(x, i);
                a.release(y, i);
                let dst = a.take(i);
                a.code.push(Inst::Arith {
                    op,
                    dst,
                    a: xr,
                    b: yl,
                });
            }
            Op::Neg(x) => {
                let xr = a.in_register(x);
                a.release(x, i);
                let dst = a.take(i);
                a.code.push(Inst::Xor {
                    dst,
                    a: xr,
                    mask: sign,
                });
            }
            Op::Sqrt(x) => {
                let xl = a.loc[x];
                a.release(x, i);
                let dst = a.take(i);
                a.code.push(Inst::Sqrt { dst, x: xl });
            }
            Op::Store(c, x) => {
                let src = match a.loc[x] {
                    Loc::Reg(r) => r,
                    src => {
                        let r = a.take(usize::MAX);
                        a.code.push(Inst::Load { dst: r, src });
                        a.owner[usize::from(r)] = None;
                        r
                    }
                };
                a.code.push(Inst::Store {
                    dst: Loc::Work(c),
                    src,
                });
                if a.home[x].is_none() {
                    a.home[x] = Some(Loc::Work(c));
                }
                a.release(x, i);
            }
            Op::Groups(sum) => {
                // Two scratch registers, free again for the sum itself.
                let acc = a.take(usize::MAX);
                let tmp = a.take(usize::MAX);
                a.owner[usize::from(acc)] = None;
                a.owner[usize::from(tmp)] = None;
                let dst = a.take(i);
                a.code.push(Inst::Groups { dst, acc, tmp, sum });
            }
            Op::Call { address, x, alpha } => {
                for r in 0..a.owner.len() {
                    a.spill(r);
                }
                let out = a.slot();
                a.code.push(Inst::Call {
                    address,
                    x: a.loc[x],
                    alpha,
                    out,
                });
                a.release(x, i);
                a.place_in_memory(i, Loc::Slot(out));
            }
        }
        // A value nobody reads frees its register (or slot) at once.
        if a.last[i].is_none() {
            a.release(i, i);
        }
        let freed = std::mem::take(&mut a.freed);
        a.free_slots.extend(freed);
    }
    (a.code, a.slots)
}

impl Allocator {
    fn place_in_memory(&mut self, v: usize, at: Loc) {
        self.loc[v] = at;
        self.home[v] = Some(at);
    }

    /// A stack slot: a free one, else a new one.
    fn slot(&mut self) -> usize {
        self.free_slots.pop().unwrap_or_else(|| {
            self.slots += 1;
            self.slots - 1
        })
    }

    /// Frees `v`'s register, and its slot once the op is written, if op `i` is its last
    /// reader.
    fn release(&mut self, v: usize, i: usize) {
        if self.last[v].is_some_and(|last| last > i) {
            return;
        }
        if let Some(Loc::Slot(s)) = self.home[v] {
            self.home[v] = None;
            self.freed.push(s);
        }
        if let Loc::Reg(r) = self.loc[v] {
            if self.owner[usize::from(r)] == Some(v) {
                self.owner[usize::from(r)] = None;
            }
        }
    }

    /// A register for value `v` (`usize::MAX`: a scratch use, freed by the caller): a free
    /// one, else the one whose value is read last, that value moved to memory.
    fn take(&mut self, v: usize) -> u8 {
        let r = if let Some(r) = self.owner.iter().position(Option::is_none) {
            r
        } else {
            let later = |r: &usize| match self.owner[*r] {
                Some(w) if w != usize::MAX => self.last[w].unwrap_or(0),
                _ => 0,
            };
            let r = (0..self.owner.len()).max_by_key(later).unwrap_or(0);
            self.spill(r);
            r
        };
        self.owner[r] = Some(v);
        let r = r as u8;
        if v != usize::MAX {
            self.loc[v] = Loc::Reg(r);
        }
        r
    }

    /// Value `v` in a register, loaded into one if it is in memory.
    fn in_register(&mut self, v: usize) -> u8 {
        if let Loc::Reg(r) = self.loc[v] {
            return r;
        }
        let src = self.loc[v];
        let r = self.take(v);
        self.code.push(Inst::Load { dst: r, src });
        r
    }

    /// Frees register `r`, its value moved to memory: its copy there if it has one, else a
    /// new stack slot.
    fn spill(&mut self, r: usize) {
        let Some(v) = self.owner[r].take() else {
            return;
        };
        if v == usize::MAX {
            return;
        }
        let at = match self.home[v] {
            Some(at) => at,
            None => {
                let at = Loc::Slot(self.slot());
                self.code.push(Inst::Store {
                    dst: at,
                    src: r as u8,
                });
                at
            }
        };
        self.place_in_memory(v, at);
    }
}

/// Code that cannot be written: an offset or frame beyond 32 bits, or an error of the
/// assembler's.
struct Unencodable;

impl From<IcedError> for Unencodable {
    fn from(_: IcedError) -> Self {
        Unencodable
    }
}

/// The largest stack frame written: 256 KiB, an eighth of a Rust thread's default stack
/// (calls and spills take one slot each, a few per program; larger frames are left to
/// Cranelift).
const MAX_FRAME: usize = 1 << 18;

/// The function's layout: lanes in all, per register, and stack slots.
struct Frame {
    lanes: usize,
    width: usize,
    slots: usize,
}

/// A vector register of either width.
#[derive(Clone, Copy)]
enum Vector {
    /// One lane: the scalar instructions on an `xmm`'s low double.
    X(AsmRegisterXmm),
    Y(AsmRegisterYmm),
    Z(AsmRegisterZmm),
}

const XMM: [AsmRegisterXmm; 16] = [
    registers::xmm0,
    registers::xmm1,
    registers::xmm2,
    registers::xmm3,
    registers::xmm4,
    registers::xmm5,
    registers::xmm6,
    registers::xmm7,
    registers::xmm8,
    registers::xmm9,
    registers::xmm10,
    registers::xmm11,
    registers::xmm12,
    registers::xmm13,
    registers::xmm14,
    registers::xmm15,
];

const YMM: [AsmRegisterYmm; 16] = [
    registers::ymm0,
    registers::ymm1,
    registers::ymm2,
    registers::ymm3,
    registers::ymm4,
    registers::ymm5,
    registers::ymm6,
    registers::ymm7,
    registers::ymm8,
    registers::ymm9,
    registers::ymm10,
    registers::ymm11,
    registers::ymm12,
    registers::ymm13,
    registers::ymm14,
    registers::ymm15,
];

const ZMM: [AsmRegisterZmm; 32] = [
    registers::zmm0,
    registers::zmm1,
    registers::zmm2,
    registers::zmm3,
    registers::zmm4,
    registers::zmm5,
    registers::zmm6,
    registers::zmm7,
    registers::zmm8,
    registers::zmm9,
    registers::zmm10,
    registers::zmm11,
    registers::zmm12,
    registers::zmm13,
    registers::zmm14,
    registers::zmm15,
    registers::zmm16,
    registers::zmm17,
    registers::zmm18,
    registers::zmm19,
    registers::zmm20,
    registers::zmm21,
    registers::zmm22,
    registers::zmm23,
    registers::zmm24,
    registers::zmm25,
    registers::zmm26,
    registers::zmm27,
    registers::zmm28,
    registers::zmm29,
    registers::zmm30,
    registers::zmm31,
];

/// Either width's form of a vector instruction, register or memory as its last operand
/// (`$scalar` on one lane's `xmm`, `$name` on `ymm`, `$wide` on `zmm`, `$name` by default).
macro_rules! vector_op {
    ($asm:expr, $frame:expr, $name:ident, $scalar:ident, $dst:expr, $a:expr, $b:expr) => {
        vector_op!($asm, $frame, $name, $name, $scalar, $dst, $a, $b)
    };
    ($asm:expr, $frame:expr, $name:ident, $wide:ident, $scalar:ident, $dst:expr, $a:expr, $b:expr) => {{
        let (dst, a) = ($frame.vector($dst), $frame.vector($a));
        match ($b, dst, a) {
            (Operand::Reg(b), Vector::X(d), Vector::X(a)) => {
                $asm.$scalar(d, a, XMM[usize::from(b)])
            }
            (Operand::Mem(m), Vector::X(d), Vector::X(a)) => $asm.$scalar(d, a, m),
            (Operand::Reg(b), Vector::Y(d), Vector::Y(a)) => $asm.$name(d, a, YMM[usize::from(b)]),
            (Operand::Reg(b), Vector::Z(d), Vector::Z(a)) => $asm.$wide(d, a, ZMM[usize::from(b)]),
            (Operand::Mem(m), Vector::Y(d), Vector::Y(a)) => $asm.$name(d, a, m),
            (Operand::Mem(m), Vector::Z(d), Vector::Z(a)) => $asm.$wide(d, a, m),
            _ => unreachable!("one frame has one width"),
        }
    }};
}

/// A register or a memory operand.
enum Operand {
    Reg(u8),
    Mem(AsmMemoryOperand),
}

impl Frame {
    fn vector(&self, r: u8) -> Vector {
        if self.width == 8 {
            Vector::Z(ZMM[usize::from(r)])
        } else if self.width == 1 {
            Vector::X(XMM[usize::from(r)])
        } else {
            Vector::Y(YMM[usize::from(r)])
        }
    }

    /// Bytes of one vector.
    fn bytes(&self) -> usize {
        8 * self.width
    }

    /// The address of `at` (in memory), plus `lane` doubles.
    fn address(
        &self,
        at: Loc,
        lane: usize,
        pool: &[CodeLabel],
    ) -> Result<AsmMemoryOperand, Unencodable> {
        let offset = |bytes: usize| i32::try_from(bytes + 8 * lane).map_err(|_| Unencodable);
        Ok(match at {
            Loc::Work(i) => ptr(rbx + offset(8 * self.lanes * i)?),
            Loc::Slot(s) => ptr(rsp + offset(self.bytes() * s)?),
            Loc::Pool(p) => ptr(pool[p]) + offset(0)?,
            Loc::Reg(_) => return Err(Unencodable),
        })
    }

    fn operand(&self, at: Loc, pool: &[CodeLabel]) -> Result<Operand, Unencodable> {
        Ok(match at {
            Loc::Reg(r) => Operand::Reg(r),
            at => Operand::Mem(self.address(at, 0, pool)?),
        })
    }

    /// The function: save the two registers the loop keeps, reserve the slots, run the
    /// instructions once per `width` lanes, return; then the constant pool.
    fn encode(
        &self,
        code: &[Inst],
        constants: &[f64],
        weights: &[[f64; 4]],
    ) -> Result<Vec<u8>, Unencodable> {
        let mut asm = CodeAssembler::new(64)?;
        let pool: Vec<CodeLabel> = constants.iter().map(|_| asm.create_label()).collect();
        let vectors: Vec<CodeLabel> = weights.iter().map(|_| asm.create_label()).collect();
        // Entered with `rsp` 8 bytes past a multiple of 16: two pushes and a frame of 8 more
        // than a multiple of 16 align it for the shims' calls.
        let frame = self.bytes() * self.slots + 8;
        let frame = frame + (16 - frame % 16) % 16 + 8;
        if frame > MAX_FRAME {
            return Err(Unencodable);
        }
        let frame = i32::try_from(frame).map_err(|_| Unencodable)?;
        asm.push(rbx)?;
        asm.push(r12)?;
        asm.sub(rsp, frame)?;
        // A frame of more than a page is touched a page at a time from the top (a stack
        // probe, as compilers write for large frames), so that a guard page below the stack
        // is met rather than stepped over.
        for page in 1..=(frame - 8) / 4096 {
            asm.or(qword_ptr(rsp + (frame - 8 - 4096 * page)), 0)?;
        }
        asm.mov(rbx, rdi)?;
        let end = i32::try_from(8 * self.lanes).map_err(|_| Unencodable)?;
        asm.lea(r12, ptr(rdi + end))?;
        let mut pass = asm.create_label();
        asm.set_label(&mut pass)?;
        for inst in code {
            self.instruction(&mut asm, inst, &pool, &vectors)?;
        }
        asm.add(rbx, i32::try_from(self.bytes()).map_err(|_| Unencodable)?)?;
        asm.cmp(rbx, r12)?;
        asm.jb(pass)?;
        asm.add(rsp, frame)?;
        asm.pop(r12)?;
        asm.pop(rbx)?;
        asm.vzeroupper()?;
        asm.ret()?;
        for (label, &c) in pool.iter().zip(constants) {
            let mut label = *label;
            asm.set_label(&mut label)?;
            // Two doubles at least: one lane's `vxorpd` reads an `xmm`'s 16 bytes.
            let bytes: Vec<u8> = std::iter::repeat_n(c.to_le_bytes(), self.width.max(2))
                .flatten()
                .collect();
            asm.db(&bytes)?;
        }
        for (label, w) in vectors.iter().zip(weights) {
            let mut label = *label;
            asm.set_label(&mut label)?;
            let bytes: Vec<u8> = w.iter().flat_map(|w| w.to_le_bytes()).collect();
            asm.db(&bytes)?;
        }
        Ok(asm.assemble(0)?)
    }

    fn instruction(
        &self,
        asm: &mut CodeAssembler,
        inst: &Inst,
        pool: &[CodeLabel],
        vectors: &[CodeLabel],
    ) -> Result<(), Unencodable> {
        let written: Result<(), IcedError> = match *inst {
            Inst::Load { dst, src } => {
                let m = self.address(src, 0, pool)?;
                match self.vector(dst) {
                    Vector::X(d) => asm.vmovsd(d, m),
                    Vector::Y(d) => asm.vmovupd(d, m),
                    Vector::Z(d) => asm.vmovupd(d, m),
                }
            }
            Inst::Store { dst, src } => {
                let m = self.address(dst, 0, pool)?;
                match self.vector(src) {
                    Vector::X(s) => asm.vmovsd(m, s),
                    Vector::Y(s) => asm.vmovupd(m, s),
                    Vector::Z(s) => asm.vmovupd(m, s),
                }
            }
            Inst::Arith { op, dst, a, b } => {
                let b = self.operand(b, pool)?;
                match op {
                    Arith::Add => vector_op!(asm, self, vaddpd, vaddsd, dst, a, b),
                    Arith::Sub => vector_op!(asm, self, vsubpd, vsubsd, dst, a, b),
                    Arith::Mul => vector_op!(asm, self, vmulpd, vmulsd, dst, a, b),
                    Arith::Div => vector_op!(asm, self, vdivpd, vdivsd, dst, a, b),
                    Arith::Min => vector_op!(asm, self, vminpd, vminsd, dst, a, b),
                    // On one lane the bitwise operations read an `xmm`'s 16 bytes from memory:
                    // a pool entry holds two doubles; a coefficient of `|a|`'s operand has
                    // the `|a|`'s own coefficients after it in the work array, and a stack
                    // slot the next slot or the frame's eight spare bytes. The `zmm` forms
                    // are AVX-512F's integer ones (`vandpd` on `zmm` needs AVX-512DQ), on
                    // the same bits.
                    Arith::And => vector_op!(asm, self, vandpd, vpandq, vandpd, dst, a, b),
                    Arith::Xor => vector_op!(asm, self, vxorpd, vpxorq, vxorpd, dst, a, b),
                }
            }
            Inst::Sqrt { dst, x } => match (self.operand(x, pool)?, self.vector(dst)) {
                (Operand::Reg(x), Vector::X(d)) => {
                    asm.vsqrtsd(d, XMM[usize::from(x)], XMM[usize::from(x)])
                }
                (Operand::Mem(m), Vector::X(d)) => asm.vsqrtsd(d, d, m),
                (Operand::Reg(x), Vector::Y(d)) => asm.vsqrtpd(d, YMM[usize::from(x)]),
                (Operand::Reg(x), Vector::Z(d)) => asm.vsqrtpd(d, ZMM[usize::from(x)]),
                (Operand::Mem(m), Vector::Y(d)) => asm.vsqrtpd(d, m),
                (Operand::Mem(m), Vector::Z(d)) => asm.vsqrtpd(d, m),
            },
            Inst::Xor { dst, a, mask } => {
                let m = self.address(Loc::Pool(mask), 0, pool)?;
                // `vxorpd` on `zmm` needs AVX-512DQ; `vpxorq`, the same bits, AVX-512F.
                match (self.vector(dst), self.vector(a)) {
                    (Vector::X(d), Vector::X(a)) => asm.vxorpd(d, a, m),
                    (Vector::Y(d), Vector::Y(a)) => asm.vxorpd(d, a, m),
                    (Vector::Z(d), Vector::Z(a)) => asm.vpxorq(d, a, m),
                    _ => unreachable!("one frame has one width"),
                }
            }
            Inst::Groups {
                dst,
                acc,
                tmp,
                sum:
                    Groups {
                        fwd,
                        rev,
                        groups,
                        weights,
                    },
            } => {
                let (y, x) = (|r: u8| YMM[usize::from(r)], |r: u8| XMM[usize::from(r)]);
                let work = |i: Option<usize>| {
                    i.ok_or(Unencodable)
                        .and_then(|i| self.address(Loc::Work(i), 0, pool))
                };
                for g in 0..groups {
                    let t = if g == 0 { acc } else { tmp };
                    // `rev_j … rev_{j+3}` read upwards from `rev_{j+3}`, then reversed.
                    let low = work((rev + 1).checked_sub(4 * (g + 1)))?;
                    asm.vpermpd(y(t), low, 0x1B)?;
                    if let Some(w) = weights {
                        asm.vmulpd(y(t), y(t), ptr(vectors[w + g]))?;
                    }
                    asm.vmulpd(y(t), y(t), work(Some(fwd + 4 * g))?)?;
                    if g > 0 {
                        asm.vaddpd(y(acc), y(acc), y(tmp))?;
                    }
                }
                // (p_0 + p_2, p_1 + p_3), then their sum.
                asm.vextractf128(x(tmp), y(acc), 1)?;
                asm.vaddpd(x(acc), x(acc), x(tmp))?;
                asm.vpermilpd(x(tmp), x(acc), 1)?;
                asm.vaddsd(x(dst), x(acc), x(tmp))
            }
            Inst::Call {
                address,
                x,
                alpha,
                out,
            } => {
                // The shims are SSE code: clear the upper halves first (every vector
                // register was saved to memory before this instruction).
                asm.vzeroupper()?;
                for lane in 0..self.width {
                    asm.vmovsd(registers::xmm0, self.address(x, lane, pool)?)?;
                    if let Some(alpha) = alpha {
                        asm.vmovsd(registers::xmm1, self.address(Loc::Pool(alpha), 0, pool)?)?;
                    }
                    asm.mov(rax, address as u64)?;
                    asm.call(rax)?;
                    asm.vmovsd(self.address(Loc::Slot(out), lane, pool)?, registers::xmm0)?;
                }
                Ok(())
            }
        };
        Ok(written?)
    }
}

#[cfg(test)]
mod tests {
    use super::compile_on;
    use crate::classical::integrators::taylor::TaylorField;
    use crate::classical::symbolic::taylor_tape::WorkLayout;
    use crate::classical::symbolic::{Expr, ExprOde, TaylorProgram};

    /// A program with sums, products, quotients, square roots and negations (Kepler's field
    /// with a `sin` and a general power): every operation this code writes, and the calls.
    fn program() -> TaylorProgram {
        let f = [
            "q2",
            "q3",
            "(neg (* q0 (^ (+ (* q0 q0) (* q1 q1)) -1.5)))",
            "(- (/ (sin q1) (sqrt (+ 2 (* q0 q0)))) (* q1 (^ (+ 1 (* q0 q0)) 0.3)))",
        ];
        let f: Vec<Expr> = f.iter().map(|f| Expr::parse(f).unwrap()).collect();
        let y0 = [0.8, 0.2, 0.1, 1.1];
        TaylorProgram::ode(&ExprOde::new(f, vec![], &y0, None).unwrap()).unwrap()
    }

    /// A sum of 100 sines (each with its cosine: 200 calls at order 0, each result in a stack
    /// slot until read): a frame of more than a page in `zmm` code, so that the stack is
    /// probed.
    fn many_calls() -> TaylorProgram {
        let sines: String = (1..=100).map(|i| format!(" (sin (* {i} q1))")).collect();
        let f = ["q2", "q3", "(neg q0)", &format!("(+{sines})")];
        let f: Vec<Expr> = f.iter().map(|f| Expr::parse(f).unwrap()).collect();
        let y0 = [0.8, 0.2, 0.1, 1.1];
        TaylorProgram::ode(&ExprOde::new(f, vec![], &y0, None).unwrap()).unwrap()
    }

    /// Products, `|q0|` and `|q0 q1|`: order `k` of `|a|` is `-a_k` where `a_0 < 0`, else `a_k`
    /// (a NaN and both zeros are not below zero).
    fn absolute_values() -> TaylorProgram {
        let f = ["q2", "q3", "(* q1 (abs q0))", "(abs (* q0 q1))"];
        let f: Vec<Expr> = f.iter().map(|f| Expr::parse(f).unwrap()).collect();
        let y0 = [0.8, 0.2, 0.1, 1.1];
        TaylorProgram::ode(&ExprOde::new(f, vec![], &y0, None).unwrap()).unwrap()
    }

    /// The same bits, or both NaNs: which operand's NaN an x86 operation passes on depends
    /// on the operands' order, which the code may swap where the operation commutes.
    fn same(a: f64, b: f64) -> bool {
        a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
    }

    /// Lane `l` of the four rows of a distinct state: `0.5 + 0.1 i + 0.03 l`.
    fn states<const L: usize>() -> Vec<[f64; L]> {
        (0..4)
            .map(|i| std::array::from_fn(|l| 0.5 + 0.1 * i as f64 + 0.03 * l as f64))
            .collect()
    }

    /// On 1, 2 and 5 registers (so that values are moved to the stack and back, and read
    /// from where they were stored) and on all of them, the code's coefficients of every node
    /// at the states `y` are the interpreter's bit for bit. One state's code also writes
    /// the state's coefficients into the work array's blocks, each where the stepper's
    /// transposition puts it; the lanes' code leaves the blocks alone.
    fn check<const L: usize>(program: &TaylorProgram, y: &[[f64; L]]) {
        let order = 9;
        let stride = order + 1;
        let t: [f64; L] = std::array::from_fn(|l| 0.1 * l as f64);
        // Each lane's every node, by the interpreter on that lane's state alone.
        let mut reference = program.interpreted_only();
        let want: Vec<Vec<f64>> = (0..L)
            .map(|l| {
                let state: Vec<f64> = y.iter().map(|yi| yi[l]).collect();
                let mut out = vec![0.0; 4 * stride];
                reference
                    .coefficients(t[l], &state, order, &mut out)
                    .unwrap();
                reference.work.clone()
            })
            .collect();
        let layout = WorkLayout::new(&program.nodes, 4, order);
        for registers in [Some(1), Some(2), Some(5), None] {
            let Some((code, _module)) = compile_on(
                &program.nodes,
                &program.outputs,
                L,
                Some(layout),
                order,
                registers,
            ) else {
                assert!(super::width(L).is_none(), "AVX host, no code");
                return;
            };
            // The inputs as `expand` sets them: the state's and the time's orders 0, the
            // time's order 1; everything else is the code's to write.
            let mut w = vec![[0.0; L]; layout.len()];
            for (i, yi) in y.iter().enumerate() {
                w[i * stride] = *yi;
            }
            w[4 * stride] = t;
            w[4 * stride + 1] = [1.0; L];
            // SAFETY: the code reads and writes the work array of these recurrences at
            // this order and lane count, which `w` is.
            #[allow(unsafe_code)]
            unsafe {
                let f: unsafe extern "C" fn(*mut f64) = std::mem::transmute(code);
                f(w.as_mut_ptr().cast());
            }
            let (nodes, blocks) = w.split_at(layout.blocks_start());
            for (i, g) in nodes.iter().enumerate() {
                for (l, want) in want.iter().enumerate() {
                    assert!(
                        same(g[l], want[i]),
                        "{registers:?} registers, {L} lanes, coefficient {i}, lane {l}"
                    );
                }
            }
            // The blocks as the stepper's transposition fills them (one state), or
            // untouched (lanes).
            let mut expected = vec![[0.0; L]; blocks.len()];
            for i in 0..4 {
                for j in 0..stride {
                    if L == 1 {
                        expected[layout.in_blocks(i, j) - layout.blocks_start()] =
                            std::array::from_fn(|l| want[l][i * stride + j]);
                    }
                }
            }
            for (b, (g, e)) in blocks.iter().zip(&expected).enumerate() {
                for l in 0..L {
                    assert!(
                        same(g[l], e[l]),
                        "{registers:?} registers, {L} lanes, block entry {b}, lane {l}"
                    );
                }
            }
        }
    }

    /// [`check`] on programs of every operation this code writes, for one state and in 4 and 8
    /// lanes at distinct states, with frames of a few slots and of several pages.
    #[test]
    fn spilled_code_has_the_interpreters_bits() {
        let calls = many_calls();
        let mut recorder = super::Recorder::of(&calls.nodes, &calls.outputs, 9, None, false);
        let sign = recorder.constant(-0.0);
        let (_, slots) = super::allocate(&recorder.ops, 32, sign);
        assert!(64 * slots > 4096, "{slots} slots of a zmm");
        for program in [program(), calls, absolute_values()] {
            check::<1>(&program, &states());
            check::<4>(&program, &states());
            check::<8>(&program, &states());
        }
    }

    /// `|a|` where `a_0` is below zero, above it, either zero, a NaN or infinite (the
    /// interpreter's coefficients then NaNs or infinities, bit for bit too): on one state
    /// each, and the eight of them in the lanes of 4 and 8.
    #[test]
    fn absolute_values_follow_the_sign_of_order_zero() {
        let q0 = [
            -0.7,
            0.7,
            -0.0,
            0.0,
            f64::NAN,
            -f64::NAN,
            f64::NEG_INFINITY,
            -1e-300,
        ];
        let lanes = |from: usize| -> [[f64; 4]; 4] {
            [
                std::array::from_fn(|l| q0[from + l]),
                [0.3; 4],
                [-0.2; 4],
                [0.9; 4],
            ]
        };
        let program = absolute_values();
        for &x in &q0 {
            check::<1>(&program, &[[x], [0.3], [-0.2], [0.9]]);
        }
        check::<4>(&program, &lanes(0));
        check::<4>(&program, &lanes(4));
        let eight: Vec<[f64; 8]> = (0..4)
            .map(|i| std::array::from_fn(|l| lanes(4 * (l / 4))[i][l % 4]))
            .collect();
        check::<8>(&program, &eight);
    }
}
