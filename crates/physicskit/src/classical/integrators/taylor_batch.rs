//! The adaptive Taylor method ([`taylor`](super::taylor)) on `L` members at once: one
//! expansion of a shared field computes the Taylor coefficients of `L` states, one per vector
//! lane ([`LanesField`]), and the whole step is then taken across the lanes.
//!
//! Each member's run is the one [`TaylorStepper`](super::TaylorStepper) gives it on the
//! output grid (what `integrate` with `method = taylor` does), bit for bit:
//!
//! - the lanes' coefficients are the scalar recurrences' (each lane does their operations in
//!   their order);
//! - the rest of the step is [`Taylor`](super::taylor::Taylor)'s, done on `[f64; L]` values,
//!   each lane with the scalar code's operations in its order: the norms of the state and of
//!   the last two orders, the step-size rule's radius (its `log2` and `2^y` in plain
//!   arithmetic, in vector registers), the clamp to the end, the state update by Horner
//!   (plain over the high orders, compensated over the low ones) with the double-double low
//!   words (the error-free products by FMA where the scalar code uses it, by Dekker's product
//!   where it does not), the double-double clock, and the dense output of the step's
//!   polynomial at each output time;
//! - the outputs are those of the grid, `t_i + dt` from output `i` (snapped to the end as
//!   [`TaylorStepper`](super::TaylorStepper) snaps it), each member restarting its stepper
//!   where `TaylorStepper` would; the errors (step budget, coefficients not finite, step
//!   size underflow, an output not finite) are the scalar run's.
//!
//! All running members take their steps together: after each step, each lane emits the
//! outputs its new polynomial covers; a member that has all its outputs (or fails) hands its
//! lane to the next member, so lanes stay busy while members take different numbers of steps;
//! a lane without a member computes a copy of a running lane's state, and its results are
//! dropped. Nothing is allocated per step.
//!
//! A member whose run fails is reported with its run's error. Per-step data (energy errors,
//! events, Lyapunov exponents) is not computed here: callers that need it run members one at
//! a time.

use crate::classical::core::{Error, Result, TimeGrid};
use crate::classical::integrators::taylor::{check_tolerances, order_for, same_time, StepCost};
use crate::classical::integrators::taylor_arith::{
    two_product, two_product_fused, two_sum, StepRule, COMPENSATED_ORDERS,
};
use crate::classical::integrators::Tolerances;

/// A field whose Taylor coefficients can be computed for `L` states at once, one per lane.
pub trait LanesField<const L: usize> {
    /// Dimension of the state.
    fn dim(&self) -> usize;

    /// The work of a step, by which the order is chosen: the same as the
    /// [`TaylorField::step_cost`] of the field these lanes run (the default: the same default),
    /// so that each member steps at the order it would alone.
    ///
    /// [`TaylorField::step_cost`]: super::taylor::TaylorField::step_cost
    fn step_cost(&self) -> StepCost {
        StepCost::generic(self.dim())
    }

    /// Expands the solution through `(t[l], y[.][l])` for every lane `l` (`y` holds `dim`
    /// components, each an `[f64; L]`) to `order`; the coefficients stay in the field until
    /// the next expansion ([`coefficients`](Self::coefficients), [`lane`](Self::lane)).
    ///
    /// # Errors
    /// An `order` or a state length the field cannot expand.
    fn expand(&mut self, t: &[f64; L], y: &[[f64; L]], order: usize) -> Result<()>;

    /// The coefficients of the last expansion, every lane's: `dim` rows of `order + 1`
    /// (row `i` holding `y_i^[0..=order]`, as [`TaylorField::coefficients`] fills them),
    /// each an `[f64; L]`.
    ///
    /// [`TaylorField::coefficients`]: super::taylor::TaylorField::coefficients
    fn coefficients(&self) -> &[[f64; L]];

    /// Lane `lane`'s coefficients of the last expansion into `coefficients` (`dim` rows of
    /// `order + 1`, as [`TaylorField::coefficients`] fills them).
    ///
    /// [`TaylorField::coefficients`]: super::taylor::TaylorField::coefficients
    fn lane(&self, lane: usize, coefficients: &mut [f64]) {
        for (c, w) in coefficients.iter_mut().zip(self.coefficients()) {
            *c = w[lane];
        }
    }
}

/// How the error-free product is computed: as the scalar stepper computes it on this CPU
/// (one FMA where the CPU has it, else Dekker's product), and which vector instructions
/// the lanes' loops are compiled for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Isa {
    /// Dekker's product, no FMA (the scalar path of CPUs without FMA).
    Plain,
    /// FMA, without wide vectors.
    #[cfg(target_arch = "x86_64")]
    Fma,
    /// FMA and AVX2 (vectors of four doubles).
    #[cfg(target_arch = "x86_64")]
    Avx2,
    /// FMA and AVX-512 (vectors of eight doubles).
    #[cfg(target_arch = "x86_64")]
    Avx512,
}

impl Isa {
    fn detect() -> Self {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("fma") {
            if std::arch::is_x86_feature_detected!("avx512f") {
                return Self::Avx512;
            }
            if std::arch::is_x86_feature_detected!("avx2") {
                return Self::Avx2;
            }
            return Self::Fma;
        }
        Self::Plain
    }

    fn fused(self) -> bool {
        self != Self::Plain
    }
}

/// Horner (plain over the high orders, compensated over the low ones) of `dim` rows of `n1`
/// coefficients in lanes (`c`, row-major, each an `[f64; L]`) at `x[l]` in lane `l`, plus the
/// low words `lo_in`, into `out` and the rounding's errors into `out_lo`: per lane the
/// operations of the scalar stepper's state update in its order (`taylor.rs`'s
/// `horner_blocks`). Error-free products by FMA if `FUSED`.
/// Two rows at a time ([`horner_rows`]): each row's chain of products and sums waits on the
/// latency of the one before, and two rows' chains overlap.
#[inline(always)]
fn horner_lanes<const L: usize, const FUSED: bool>(
    c: &[[f64; L]],
    n1: usize,
    x: &[f64; L],
    lo_in: &[[f64; L]],
    out: &mut [[f64; L]],
    out_lo: &mut [[f64; L]],
) {
    let pairs = c.len() / n1 / 2;
    let (c2, c1) = c.split_at(2 * n1 * pairs);
    let (lo2, lo1) = lo_in.split_at(2 * pairs);
    let (out2, out1) = out.split_at_mut(2 * pairs);
    let (out_lo2, out_lo1) = out_lo.split_at_mut(2 * pairs);
    for (((rows, lo_in), out), out_lo) in c2
        .chunks_exact(2 * n1)
        .zip(lo2.chunks_exact(2))
        .zip(out2.chunks_exact_mut(2))
        .zip(out_lo2.chunks_exact_mut(2))
    {
        horner_rows::<L, 2, FUSED>(rows, n1, x, lo_in, out, out_lo);
    }
    if !c1.is_empty() {
        horner_rows::<L, 1, FUSED>(c1, n1, x, lo1, out1, out_lo1);
    }
}

/// [`horner_lanes`] on `R` rows (`rows` holds `R` rows of `n1`), their steps interleaved
/// order by order; each row's operations are those of one row alone, in its order.
#[inline(always)]
fn horner_rows<const L: usize, const R: usize, const FUSED: bool>(
    rows: &[[f64; L]],
    n1: usize,
    x: &[f64; L],
    lo_in: &[[f64; L]],
    out: &mut [[f64; L]],
    out_lo: &mut [[f64; L]],
) {
    let product = if FUSED {
        two_product_fused
    } else {
        two_product
    };
    let mut s: [[f64; L]; R] = std::array::from_fn(|r| rows[r * n1 + n1 - 1]);
    let mut err = [[0.0; L]; R];
    let plain = COMPENSATED_ORDERS.min(n1 - 1);
    for k in (plain..n1 - 1).rev() {
        for (r, s) in s.iter_mut().enumerate() {
            let ck = &rows[r * n1 + k];
            for l in 0..L {
                s[l] = s[l] * x[l] + ck[l];
            }
        }
    }
    for k in (0..plain).rev() {
        for (r, (s, err)) in s.iter_mut().zip(err.iter_mut()).enumerate() {
            let ck = &rows[r * n1 + k];
            for l in 0..L {
                let (p, pi) = product(s[l], x[l]);
                let (sum, sigma) = two_sum(p, ck[l]);
                s[l] = sum;
                err[l] = err[l] * x[l] + (pi + sigma);
            }
        }
    }
    for (r, (s, err)) in s.iter().zip(&err).enumerate() {
        for l in 0..L {
            let (hi, low) = two_sum(s[l], err[l] + lo_in[r][l]);
            out[r][l] = hi;
            out_lo[r][l] = low;
        }
    }
}

/// The step-size rule's radius of each lane from the largest `|c|` of the rule's orders
/// ([`StepRule::norm_orders`]) over the rows of `c` (`dim` rows of `p + 1`), lane by lane (in
/// row order, by `f64::max`, as the scalar step takes them).
#[inline(always)]
fn radii<const L: usize>(c: &[[f64; L]], p: usize, rule: &StepRule) -> [f64; L] {
    let (mut norm, mut second_last, mut last) = ([0.0_f64; L], [0.0_f64; L], [0.0_f64; L]);
    let [first, before_last, final_order] = rule.norm_orders();
    for row in c.chunks_exact(p + 1) {
        for l in 0..L {
            norm[l] = norm[l].max(row[first][l].abs());
            second_last[l] = second_last[l].max(row[before_last][l].abs());
            last[l] = last[l].max(row[final_order][l].abs());
        }
    }
    let mut rho = [0.0; L];
    for (l, rho) in rho.iter_mut().enumerate() {
        *rho = rule.radius([norm[l], second_last[l], last[l]]);
    }
    rho
}

/// Whether each lane of `rows` is finite in every row: `x · 0` is a zero for finite `x` and NaN
/// otherwise, so a lane's sum of them is a zero exactly when all its values are finite (lane
/// by lane, so in vector registers).
#[inline(always)]
fn finite_lanes<const L: usize>(rows: &[[f64; L]]) -> [bool; L] {
    let mut zero = [0.0_f64; L];
    for v in rows {
        for l in 0..L {
            zero[l] += v[l] * 0.0;
        }
    }
    zero.map(|z| z == 0.0)
}

/// Whether every coefficient of lane `lane` in `c` is finite.
fn lane_finite<const L: usize>(c: &[[f64; L]], lane: usize) -> bool {
    c.iter().all(|v| v[lane].is_finite())
}

/// Each lane's step from its radius `rho` (zero where it takes none), and whether the rule
/// refused a lane that steps: [`StepRule::try_step`] lane by lane, its coefficients taken as
/// finite (`integrate_batch` finds those that are not after the update).
#[inline(always)]
fn steps<const L: usize>(
    batch: &Batch<L>,
    rho: [f64; L],
    stepping: [bool; L],
) -> ([f64; L], [bool; L]) {
    let mut h = [0.0; L];
    let mut refused = [false; L];
    for l in 0..L {
        let remaining = (batch.t_bound - batch.t[l]) - batch.t_lo[l];
        let (step, ok) = batch.rule.try_step(rho[l], true, batch.t[l], remaining);
        h[l] = if stepping[l] && ok { step } else { 0.0 };
        refused[l] = stepping[l] && !ok;
    }
    (h, refused)
}

/// The step's kernels compiled for one instruction set (called only where the CPU has its
/// features): [`Batch::update`] (error-free products by FMA if `$fused`), [`steps`] and
/// [`radii`]. Rust contracts no multiplication and addition into an FMA, so
/// each gives the plain build's bits.
macro_rules! kernels {
    ($update:ident, $steps:ident, $radii:ident, $features:literal, $fused:literal) => {
        #[cfg(target_arch = "x86_64")]
        #[target_feature(enable = $features)]
        fn $update<const L: usize>(
            batch: &mut Batch<L>,
            c: &[[f64; L]],
            h: &[f64; L],
        ) -> [bool; L] {
            batch.update::<$fused>(c, h)
        }

        #[cfg(target_arch = "x86_64")]
        #[target_feature(enable = $features)]
        fn $steps<const L: usize>(
            batch: &Batch<L>,
            rho: [f64; L],
            stepping: [bool; L],
        ) -> ([f64; L], [bool; L]) {
            steps(batch, rho, stepping)
        }

        #[cfg(target_arch = "x86_64")]
        #[target_feature(enable = $features)]
        fn $radii<const L: usize>(c: &[[f64; L]], p: usize, rule: &StepRule) -> [f64; L] {
            radii(c, p, rule)
        }
    };
}
kernels!(
    update_avx512,
    steps_avx512,
    radii_avx512,
    "avx512f,fma",
    true
);
kernels!(update_avx2, steps_avx2, radii_avx2, "avx2,fma", true);
kernels!(update_fma, steps_fma, radii_fma, "fma", true);

impl Isa {
    /// The state update and the clocks ([`Batch::update`]) on this instruction set.
    #[inline]
    fn update<const L: usize>(
        self,
        batch: &mut Batch<L>,
        c: &[[f64; L]],
        h: &[f64; L],
    ) -> [bool; L] {
        // SAFETY (each arm): `detect` chose the variant because the CPU has the features
        // the function enables.
        #[allow(unsafe_code)]
        match self {
            Self::Plain => batch.update::<false>(c, h),
            #[cfg(target_arch = "x86_64")]
            Self::Fma => unsafe { update_fma(batch, c, h) },
            #[cfg(target_arch = "x86_64")]
            Self::Avx2 => unsafe { update_avx2(batch, c, h) },
            #[cfg(target_arch = "x86_64")]
            Self::Avx512 => unsafe { update_avx512(batch, c, h) },
        }
    }

    /// [`steps`] on this instruction set.
    #[inline]
    fn steps<const L: usize>(
        self,
        batch: &Batch<L>,
        rho: [f64; L],
        stepping: [bool; L],
    ) -> ([f64; L], [bool; L]) {
        // SAFETY (each arm): `detect` chose the variant because the CPU has the features
        // the function enables.
        #[allow(unsafe_code)]
        match self {
            Self::Plain => steps(batch, rho, stepping),
            #[cfg(target_arch = "x86_64")]
            Self::Fma => unsafe { steps_fma(batch, rho, stepping) },
            #[cfg(target_arch = "x86_64")]
            Self::Avx2 => unsafe { steps_avx2(batch, rho, stepping) },
            #[cfg(target_arch = "x86_64")]
            Self::Avx512 => unsafe { steps_avx512(batch, rho, stepping) },
        }
    }

    /// [`radii`] on this instruction set.
    #[inline]
    fn radii<const L: usize>(self, c: &[[f64; L]], p: usize, rule: &StepRule) -> [f64; L] {
        // SAFETY (each arm): `detect` chose the variant because the CPU has the features
        // the function enables.
        #[allow(unsafe_code)]
        match self {
            Self::Plain => radii(c, p, rule),
            #[cfg(target_arch = "x86_64")]
            Self::Fma => unsafe { radii_fma(c, p, rule) },
            #[cfg(target_arch = "x86_64")]
            Self::Avx2 => unsafe { radii_avx2(c, p, rule) },
            #[cfg(target_arch = "x86_64")]
            Self::Avx512 => unsafe { radii_avx512(c, p, rule) },
        }
    }
}

/// Horner (plain, then compensated, as [`horner_lanes`]) of lane `lane` of the rows `c`
/// (`n1` coefficients each) at `x`, plus
/// the low words `lo`, into `out`: the scalar stepper's dense output (`horner_blocks`
/// without the low words out), error-free products by FMA if `fused`.
fn horner_lane<const L: usize>(
    c: &[[f64; L]],
    n1: usize,
    lane: usize,
    x: f64,
    lo: &[[f64; L]],
    out: &mut [f64],
    fused: bool,
) {
    for ((row, lo), o) in c.chunks_exact(n1).zip(lo).zip(out.iter_mut()) {
        let mut s = row[n1 - 1][lane];
        let mut err = 0.0;
        let plain = COMPENSATED_ORDERS.min(n1 - 1);
        for ck in row[plain..n1 - 1].iter().rev() {
            s = s * x + ck[lane];
        }
        for ck in row[..plain].iter().rev() {
            let (p, pi) = if fused {
                two_product_fused(s, x)
            } else {
                two_product(s, x)
            };
            let (sum, sigma) = two_sum(p, ck[lane]);
            s = sum;
            err = err * x + (pi + sigma);
        }
        *o = two_sum(s, err + lo[lane]).0;
    }
}

/// The members in the lanes and their steppers' state, lane by lane (see the module
/// documentation).
struct Batch<const L: usize> {
    dim: usize,
    order: usize,
    tolerances: Tolerances,
    t_bound: f64,
    /// The step-size rule at the run's order, the scalar stepper's.
    rule: StepRule,
    isa: Isa,
    /// The member running in each lane.
    member: [Option<usize>; L],
    /// The output being computed (`1..=n_steps`), its time once begun, and the direction of
    /// the run at its beginning.
    step: [usize; L],
    target: [Option<f64>; L],
    direction: [f64; L],
    /// Whether the lane's stepper is set up (for its member's current run).
    started: [bool; L],
    /// The last output's time; the last output itself is `out`.
    out_t: [f64; L],
    out: Vec<[f64; L]>,
    /// The clock (double-double), the start of the current polynomial's step, its length
    /// (0 before the first step), the steps taken.
    t: [f64; L],
    t_lo: [f64; L],
    start: [f64; L],
    start_t_lo: [f64; L],
    h: [f64; L],
    accepted: [u64; L],
    /// The state at `t` as a double-double (`y + lo`), and the low words of the current
    /// polynomial's start.
    y: Vec<[f64; L]>,
    lo: Vec<[f64; L]>,
    start_lo: Vec<[f64; L]>,
    /// One output.
    scratch: Vec<f64>,
}

/// What a lane does next.
enum Serve {
    /// Its member needs a step.
    Step,
    /// Its member has every output, or failed: the lane is free.
    Free,
}

impl<const L: usize> Batch<L> {
    fn new(dim: usize, cost: &StepCost, tolerances: Tolerances, t_bound: f64) -> Self {
        let order = order_for(&tolerances, cost);
        Self {
            dim,
            order,
            tolerances,
            t_bound,
            rule: StepRule::new(&tolerances, order),
            isa: Isa::detect(),
            member: [None; L],
            step: [1; L],
            target: [None; L],
            direction: [0.0; L],
            started: [false; L],
            out_t: [f64::NAN; L],
            out: vec![[0.0; L]; dim],
            t: [0.0; L],
            t_lo: [0.0; L],
            start: [0.0; L],
            start_t_lo: [0.0; L],
            h: [0.0; L],
            accepted: [0; L],
            y: vec![[0.0; L]; dim],
            lo: vec![[0.0; L]; dim],
            start_lo: vec![[0.0; L]; dim],
            scratch: vec![0.0; dim],
        }
    }

    /// Starts member `member` from `y0` in lane `l`.
    fn load(&mut self, l: usize, member: usize, y0: &[f64]) {
        self.member[l] = Some(member);
        self.step[l] = 1;
        self.target[l] = None;
        self.started[l] = false;
        self.out_t[l] = f64::NAN;
        for (o, v) in self.out.iter_mut().zip(y0) {
            o[l] = *v;
        }
    }

    /// Frees lane `l`, passing its member's error to `failed`.
    fn fail(&mut self, l: usize, e: Error, failed: &mut impl FnMut(usize, Error)) -> Serve {
        if let Some(member) = self.member[l].take() {
            failed(member, e);
        }
        Serve::Free
    }

    /// A fresh stepper in lane `l` at `(t0, out)`: `Taylor::new`'s state and checks.
    fn restart(&mut self, l: usize, t0: f64) -> Result<()> {
        check_tolerances(&self.tolerances)?;
        if let Some(bad) = self.out.iter().map(|o| o[l]).find(|v| !v.is_finite()) {
            return Err(Error::invalid("y0", bad, "must be finite"));
        }
        for i in 0..self.dim {
            self.y[i][l] = self.out[i][l];
            self.lo[i][l] = 0.0;
            self.start_lo[i][l] = 0.0;
        }
        (self.t[l], self.t_lo[l]) = (t0, 0.0);
        (self.start[l], self.start_t_lo[l]) = (t0, 0.0);
        self.h[l] = 0.0;
        self.accepted[l] = 0;
        self.started[l] = true;
        Ok(())
    }

    /// The lanes whose member needs a step and nothing else: a target the current polynomial
    /// does not reach, the clock short of the end, steps left. That is what
    /// [`serve`](Self::serve) finds in most lanes after most steps; here by its comparisons,
    /// for every lane at once (a lane without a target compares a NaN, which is false, and
    /// goes to `serve`).
    #[inline(always)]
    // Exact comparison: the clock lands on the end exactly.
    #[allow(clippy::float_cmp)]
    fn needs_step(&self) -> [bool; L] {
        std::array::from_fn(|l| {
            let target = self.target[l].unwrap_or(f64::NAN);
            let from_start = (target - self.start[l]) - self.start_t_lo[l];
            self.member[l].is_some()
                && self.h[l] != 0.0
                && from_start * self.direction[l] > self.h[l].abs()
                && self.t[l] != self.t_bound
                && self.accepted[l] < self.tolerances.max_steps
        })
    }

    /// Runs lane `l`'s member on the current polynomial (the last step's, its coefficients
    /// `c`): its outputs (each passed to `output(member, step, y)`) until it needs a step,
    /// has all its outputs, or fails (into `failed`): `TaylorStepper::advance` and
    /// `Taylor::advance` up to the expansion.
    // Exact comparisons: as the scalar stepper's, a grid time beyond the end, the clock at
    // the end, an output at the clock.
    #[allow(clippy::float_cmp)]
    fn serve(
        &mut self,
        l: usize,
        c: &[[f64; L]],
        grid: &TimeGrid,
        output: &mut impl FnMut(usize, usize, &[f64]),
        failed: &mut impl FnMut(usize, Error),
    ) -> Serve {
        let Some(member) = self.member[l] else {
            return Serve::Free;
        };
        let (n, t_bound, dt) = (grid.n_steps(), self.t_bound, grid.dt());
        let n1 = self.order + 1;
        while self.step[l] <= n {
            let target = match self.target[l] {
                Some(target) => target,
                None => {
                    let t = grid.time(self.step[l] - 1);
                    let mut target = t + dt;
                    if same_time(target, t_bound) {
                        target = t_bound;
                    } else if (target - t_bound) * (t_bound - t).signum() > 0.0 {
                        let e = Error::InvalidArgument {
                            name: "h".into(),
                            reason: format!("t + h = {target} lies beyond the end {t_bound}"),
                        };
                        return self.fail(l, e, failed);
                    }
                    if !self.started[l] || !same_time(t, self.out_t[l]) {
                        if let Err(e) = self.restart(l, t) {
                            return self.fail(l, e, failed);
                        }
                    }
                    self.target[l] = Some(target);
                    self.direction[l] = (t_bound - self.t[l]).signum();
                    target
                }
            };
            // The current polynomial covers the target?
            let covered = if self.h[l] != 0.0 {
                let from_start = (target - self.start[l]) - self.start_t_lo[l];
                if from_start * self.direction[l] <= self.h[l].abs() {
                    horner_lane(
                        c,
                        n1,
                        l,
                        from_start,
                        &self.start_lo,
                        &mut self.scratch,
                        self.isa.fused(),
                    );
                    true
                } else {
                    false
                }
            } else if target == self.t[l] {
                for (s, y) in self.scratch.iter_mut().zip(&self.y) {
                    *s = y[l];
                }
                true
            } else {
                false
            };
            if !covered {
                if self.t[l] == t_bound {
                    let e = Error::invalid("t", target, "lies beyond the end of the integration");
                    return self.fail(l, e, failed);
                }
                if self.accepted[l] >= self.tolerances.max_steps {
                    let e = Error::StepSizeTooSmall {
                        t: self.t[l],
                        step: self.h[l],
                        reason: format!(
                            "the step budget max_steps = {} is spent; raise max_steps or \
                             loosen the tolerances",
                            self.tolerances.max_steps
                        ),
                    };
                    return self.fail(l, e, failed);
                }
                return Serve::Step;
            }
            if !self.scratch.iter().all(|v| v.is_finite()) {
                let e = Error::NonFinite {
                    name: "state".into(),
                    t: target,
                };
                return self.fail(l, e, failed);
            }
            for (o, v) in self.out.iter_mut().zip(&self.scratch) {
                o[l] = *v;
            }
            self.out_t[l] = target;
            output(member, self.step[l], &self.scratch);
            self.step[l] += 1;
            self.target[l] = None;
        }
        self.member[l] = None;
        Serve::Free
    }

    /// The step size of lane `l` from the clock `(t, t_lo)` toward the end on an expansion of
    /// radius `rho` whose coefficients are finite or not (`Taylor::expand`'s rule), or its
    /// error.
    fn step_size(&self, rho: f64, finite: bool, (t, t_lo): (f64, f64)) -> Result<f64> {
        self.rule.step(rho, finite, t, (self.t_bound - t) - t_lo)
    }

    /// Takes the step of length `h[l]` in every lane on the coefficients `c`: the state
    /// update and the clock (`Taylor::take`); returns whether each lane's new state is finite.
    fn take(&mut self, c: &[[f64; L]], h: &[f64; L]) -> [bool; L] {
        std::mem::swap(&mut self.lo, &mut self.start_lo);
        self.isa.update(self, c, h)
    }

    /// [`take`](Self::take)'s work after the swap of the low words: the state by
    /// [`horner_lanes`] from the step's start, then [`clocks`](Self::clocks); returns whether
    /// each lane's new state is finite ([`finite_lanes`]). Error-free products by FMA if
    /// `FUSED`.
    #[inline(always)]
    fn update<const FUSED: bool>(&mut self, c: &[[f64; L]], h: &[f64; L]) -> [bool; L] {
        horner_lanes::<L, FUSED>(
            c,
            self.order + 1,
            h,
            &self.start_lo,
            &mut self.y,
            &mut self.lo,
        );
        self.clocks(h);
        finite_lanes(&self.y)
    }

    /// Each lane's clock moved on by its step `h` (to the end exactly where the step is what
    /// remains), the step's start and length kept and the step counted: without branches, so
    /// the lanes do it in vector registers.
    // Exact comparison: the step lands on the end exactly.
    #[allow(clippy::float_cmp)]
    #[inline(always)]
    fn clocks(&mut self, h: &[f64; L]) {
        for (l, &h) in h.iter().enumerate() {
            let remaining = (self.t_bound - self.t[l]) - self.t_lo[l];
            (self.start[l], self.start_t_lo[l]) = (self.t[l], self.t_lo[l]);
            let (hi, lo) = two_sum(self.t[l], h);
            let (hi, lo2) = two_sum(hi, lo + self.t_lo[l]);
            let ends = h == remaining;
            self.t[l] = if ends { self.t_bound } else { hi };
            self.t_lo[l] = if ends { 0.0 } else { lo2 };
            self.h[l] = h;
            self.accepted[l] += 1;
        }
    }
}

/// Integrates the members whose initial states are the rows of `starts` (`members x dim`,
/// row-major) on the grid `grid` by the adaptive Taylor method at `tolerances`, `L` at a
/// time on `field`: passes each output to `output(member, step, state)` (steps `1..=n_steps`,
/// in order per member) and each failed member's error to `failed(member, error)`, after
/// which that member gives no more outputs. `stop()` is asked before every step.
///
/// # Errors
/// [`Error::Interrupted`] once `stop()` says so; [`Error::DimensionMismatch`] for `starts`
/// not made of rows of the field's dimension; the field's refusal of an expansion.
pub fn integrate_batch<const L: usize, F: LanesField<L>>(
    field: &mut F,
    starts: &[f64],
    grid: &TimeGrid,
    tolerances: Tolerances,
    mut output: impl FnMut(usize, usize, &[f64]),
    mut failed: impl FnMut(usize, Error),
    stop: impl Fn() -> bool,
) -> Result<()> {
    let dim = field.dim();
    if dim == 0 || !starts.len().is_multiple_of(dim) {
        return Err(Error::DimensionMismatch {
            name: "starts".into(),
            expected: dim,
            found: starts.len(),
        });
    }
    let mut batch = Batch::<L>::new(dim, &field.step_cost(), tolerances, grid.t_end());
    let order = batch.order;
    let mut members = starts.chunks_exact(dim).enumerate();
    let mut t = [0.0; L];
    let mut stepping = [false; L];
    loop {
        let c = field.coefficients();
        let mut any = None;
        let quick = batch.needs_step();
        for (l, lane_steps) in stepping.iter_mut().enumerate() {
            *lane_steps = quick[l];
            if quick[l] {
                any = Some(l);
                continue;
            }
            loop {
                if batch.member[l].is_none() {
                    match members.next() {
                        Some((member, y0)) => batch.load(l, member, y0),
                        None => break,
                    }
                }
                if let Serve::Step = batch.serve(l, c, grid, &mut output, &mut failed) {
                    *lane_steps = true;
                    any = Some(l);
                    break;
                }
            }
        }
        let Some(running) = any else {
            return Ok(());
        };
        if stop() {
            return Err(Error::Interrupted { t: f64::NAN });
        }
        // A lane without a step to take computes a running lane's: finite work, dropped.
        for l in 0..L {
            let from = if stepping[l] { l } else { running };
            t[l] = batch.t[from];
            if from != l {
                for yi in &mut batch.y {
                    yi[l] = yi[from];
                }
            }
        }
        field.expand(&t, &batch.y, order)?;
        let c = field.coefficients();
        // The step rule as if every coefficient were finite; the lanes whose coefficients are
        // not are found after the update (below), which reads every coefficient.
        let rho = batch.isa.radii(c, order, &batch.rule);
        let (h, refused) = batch.isa.steps(&batch, rho, stepping);
        for l in 0..L {
            if refused[l] {
                let clock = (batch.t[l], batch.t_lo[l]);
                if let Err(e) = batch.step_size(rho[l], lane_finite(c, l), clock) {
                    batch.fail(l, e, &mut failed);
                }
            }
        }
        let finite = batch.take(c, &h);
        // A coefficient that is not finite leaves its lane's new state not finite: Horner's
        // products and sums keep an infinity or a NaN (an infinity times the step, zero or
        // not, is one or the other), and so do the error-free transformations of its
        // compensated orders. So only the lanes whose state is not finite are checked, and
        // those whose coefficients are not all finite fail with the scalar step's error: its
        // rule refuses such an expansion before the update, whatever the radius, at the clock
        // the step started from.
        if finite.iter().all(|&f| f) {
            continue;
        }
        for l in 0..L {
            if stepping[l] && batch.member[l].is_some() && !finite[l] && !lane_finite(c, l) {
                let clock = (batch.start[l], batch.start_t_lo[l]);
                if let Err(e) = batch.step_size(rho[l], false, clock) {
                    batch.fail(l, e, &mut failed);
                }
            }
        }
    }
}
