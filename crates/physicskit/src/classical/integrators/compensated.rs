//! Compensated (Kahan) summation of the kicks and drifts of the splitting methods.
//!
//! A splitting step adds small increments to the state, `p ← p + k h F(q)` and
//! `q ← q + d h M⁻¹ p`, `2 s + 1` times for `s` drifts. Each addition rounds to the precision
//! of the state, half an ulp of `|q|` or `|p|` however small the increment, and these errors
//! random-walk: `kahan_li8` (`s = 17`) makes 35 per coordinate and step. Compensated summation
//! (W. Kahan, "Further remarks on reducing truncation errors", Comm. ACM 8 (1965) 40; E. Hairer,
//! C. Lubich, G. Wanner, *Geometric Numerical Integration*, 2nd ed. (2006), §VIII.5 "Reducing
//! round-off error") recovers the rounding error of each addition exactly with Dekker's
//! Fast2Sum,
//!
//! ```text
//! s = y + a;   e = (y - s) + a        (y + a = s + e exactly when |y| >= |a|)
//! ```
//!
//! and adds it back. Here the errors of a step's additions are summed in a correction per
//! coordinate (`e_q`, `e_p`; their own rounding is `eps` times smaller) and added to the state
//! in the step's last addition to each coordinate, so a step rounds the state once, not
//! `2 s + 1` times; what is left is the rounding of the increments themselves, `~ eps |δ|`,
//! `h` times smaller than the state's ulp. (This is Ogita, Rump and Oishi's `Sum2`, "Accurate
//! sum and dot product", SIAM J. Sci. Comput. 26 (2005) 1955, with Fast2Sum: Kahan's form, which
//! adds each error into the next increment, puts three more additions on the step's critical
//! path.) The state between steps is plain `[q, p]`: nothing is carried from one step to the
//! next, so continuing a run (a second `integrate`, a session, a section) repeats its bits.
//!
//! Only the compositions of more than three drifts use the corrections: `verlet` and
//! `yoshida4` take the `PLAIN` update, `p ← p + k h F; q ← q + dm p`, whose rounding is far
//! below their truncation error at any useful step, and for which the corrections cost 1.3x to
//! 2.7x per step (benchmarks/README.md).
//!
//! The drift is arranged for a short critical path. With `p` the momentum before the kick
//! and `dm = d h M⁻¹`, the new position is
//!
//! ```text
//! q + dm (p + k h F) = (q + dm p) + (dm k h) F,
//! ```
//!
//! so `c = q + dm p` and its error are computed while the force is evaluated, and after the
//! force only one multiplication and one addition remain before the next force can start (the
//! plain update `p += k h F; q += dm p` has two of each). The drift uses the momentum's rounded
//! value, as in Hairer, Lubich & Wanner (the neglected `dm e_p` is at the rounding level of the
//! increment `dm p`).
//!
//! Every operation is one IEEE multiplication or addition, in a fixed order, with no fused
//! multiply–add: the SSE2, AVX2 and AVX-512 clones of the long loops and the wasm build give the
//! same bits.

use multiversion::multiversion;

use super::lanes::Real;
use crate::classical::integrators::MassInv;

/// Shortest slices worth the indirect call into the SIMD clones below (the generic integrator
/// itself is compiled for the baseline, SSE2). Chosen by measurement: the 100-site sine-Gordon
/// chain and the 200-pendulum swarm gain from the clones, while the 32-site FPUT chain lost
/// more to the call than it gained (figures in `benchmarks/README.md`), so it stays inline.
pub(crate) const DISPATCH_MIN: usize = 64;

/// Which update a kick–drift pass performs ([`kick_drift`]'s `KIND`): a compensated drift
/// that is not the step's last, the compensated last drift (which absorbs the corrections), or
/// the plain `p ← p + kick f; q ← q + dm p` of the low-order methods (see the module docs).
pub(crate) const MIDDLE: u8 = 0;
/// The step's last compensated drift.
pub(crate) const LAST: u8 = 1;
/// A plain kick and drift, no corrections.
pub(crate) const PLAIN: u8 = 2;

/// One coordinate's kick `p ← p + kick f` and drift `q ← q + dm p_new = (q + dm p) + g f`
/// (`g = dm kick`), the errors of the three additions summed into `eq` and `ep`. In the step's
/// last drift (`KIND == LAST`), `q` absorbs `eq` instead (see the module docs); `PLAIN`
/// updates `p` then `q` with one rounding each and leaves the corrections alone.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn update<const KIND: u8, R: Real>(
    q: &mut R,
    p: &mut R,
    eq: &mut R,
    ep: &mut R,
    f: R,
    kick: f64,
    dm: f64,
    g: f64,
) {
    let (q0, p0) = (*q, *p);
    if KIND == PLAIN {
        let s = p0 + f * kick;
        *p = s;
        *q = q0 + s * dm;
        return;
    }
    let v = p0 * dm;
    let c = q0 + v;
    let w = f * g;
    if KIND == LAST {
        *q = c + (w + (((q0 - c) + v) + *eq));
    } else {
        let s = c + w;
        *eq += ((q0 - c) + v) + ((c - s) + w);
        *q = s;
    }
    let a = f * kick;
    let s = p0 + a;
    *ep += (p0 - s) + a;
    *p = s;
}

/// The step's closing kick of one coordinate: `p ← p + (k f + ep)`, the momentum's one
/// rounding of the step; `p ← p + k f` in a plain step (`PLAIN`), whose `ep` is unused.
#[inline(always)]
fn close<const PLAIN: bool, R: Real>(p: &mut R, ep: R, f: R, k: f64) {
    if PLAIN {
        *p += f * k;
    } else {
        *p += f * k + ep;
    }
}

/// `p += kick F; q += drift M⁻¹ p` on every coordinate, compensated (corrections `eq`, `ep`,
/// zero at the start of a step), in one pass; in the step's last drift (`KIND == LAST`) `q`
/// absorbs its correction; `KIND == PLAIN` sums plainly.
///
/// Up to three coordinates with uniform masses (Kepler, Hénon–Heiles, the projectile, a
/// pendulum) take a fixed-length copy of the loop: a runtime-length loop over two elements
/// spends more instructions on its own control than on the arithmetic. From [`DISPATCH_MIN`]
/// coordinates on, the loop runs in the AVX2/AVX-512 clone this CPU supports. Every path does
/// the same operations, so the length decides nothing but speed.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn kick_drift<const KIND: u8>(
    mass_inv: MassInv<'_>,
    q: &mut [f64],
    p: &mut [f64],
    eq: &mut [f64],
    ep: &mut [f64],
    force: &[f64],
    kick: f64,
    drift: f64,
) {
    match (q.len(), mass_inv) {
        (1, MassInv::Uniform(m)) => {
            fixed::<1, KIND>(q, p, eq, ep, force, kick, drift * m);
        }
        (2, MassInv::Uniform(m)) => {
            fixed::<2, KIND>(q, p, eq, ep, force, kick, drift * m);
        }
        (3, MassInv::Uniform(m)) => {
            fixed::<3, KIND>(q, p, eq, ep, force, kick, drift * m);
        }
        (n, MassInv::Uniform(m)) if n >= DISPATCH_MIN => {
            uniform_long(KIND, q, p, eq, ep, force, kick, drift * m);
        }
        (_, MassInv::Uniform(m)) => uniform::<KIND>(q, p, eq, ep, force, kick, drift * m),
        (n, MassInv::PerCoordinate(m)) if n >= DISPATCH_MIN => {
            per_coordinate_long(KIND, q, p, eq, ep, force, m, kick, drift);
        }
        (_, MassInv::PerCoordinate(m)) => {
            per_coordinate::<KIND>(q, p, eq, ep, force, m, kick, drift);
        }
    }
}

/// Compositions of at most this many drifts (`verlet`, `yoshida4`) sum plainly. Their
/// truncation error at any step worth taking is far above the rounding the compensated sums
/// remove, and the sums would multiply their cost per step (measured in
/// benchmarks/README.md, the peer comparison).
pub(crate) const PLAIN_MAX_DRIFTS: usize = 3;

/// `$run` with the const `$kind` the update kind of kick–drift pass `$i` of a step of `$s`
/// drifts, as [`SplittingStepper`], the tangent stepper and the lanes all take it: [`PLAIN`]
/// for `$s <= PLAIN_MAX_DRIFTS`, otherwise [`MIDDLE`] and, for the last pass, [`LAST`]. The one
/// place that chooses ([`substep`] on slices, [`substep_array`] on arrays); `$s` is a const
/// and, in the unrolled substep loops, `$i` a constant, so the choice compiles away.
///
/// [`SplittingStepper`]: super::splitting::SplittingStepper
macro_rules! with_pass_kind {
    ($s:expr, $i:expr, |$kind:ident| $run:expr) => {
        if $s <= PLAIN_MAX_DRIFTS {
            const $kind: u8 = PLAIN;
            $run
        } else if $i + 1 == $s {
            const $kind: u8 = LAST;
            $run
        } else {
            const $kind: u8 = MIDDLE;
            $run
        }
    };
}

/// Kick–drift pass `i` of a step of `S` drifts: [`kick_drift`] of the kind
/// [`with_pass_kind!`] chooses.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn substep<const S: usize>(
    i: usize,
    mass_inv: MassInv<'_>,
    q: &mut [f64],
    p: &mut [f64],
    eq: &mut [f64],
    ep: &mut [f64],
    force: &[f64],
    kick: f64,
    drift: f64,
) {
    with_pass_kind!(S, i, |KIND| kick_drift::<KIND>(
        mass_inv, q, p, eq, ep, force, kick, drift
    ));
}

/// Starts a step of `S` drifts: the corrections of a compensated step start at `-0.0` (the
/// first `-0.0 + e` is `e` for every `e`, so the compiler can drop it); a plain step has none.
#[inline(always)]
pub(crate) fn begin_step<const S: usize>(eq: &mut [f64], ep: &mut [f64]) {
    if S > PLAIN_MAX_DRIFTS {
        eq.fill(-0.0);
        ep.fill(-0.0);
    }
}

/// Ends a step of `S` drifts with its closing kick `p += k F`, plus the momentum corrections
/// `ep` in a compensated step (see [`substep`]).
#[inline(always)]
pub(crate) fn end_step<const S: usize>(p: &mut [f64], ep: &[f64], force: &[f64], k: f64) {
    if S <= PLAIN_MAX_DRIFTS {
        closing_kick::<true>(p, ep, force, k);
    } else {
        closing_kick::<false>(p, ep, force, k);
    }
}

/// The step's closing kick `p += k F + ep` (`p += k F` if `PLAIN`) on every coordinate,
/// fixed-length for up to three coordinates and dispatched to a SIMD clone from
/// [`DISPATCH_MIN`] on, as in [`kick_drift`].
#[inline(always)]
fn closing_kick<const PLAIN: bool>(p: &mut [f64], ep: &[f64], force: &[f64], k: f64) {
    #[inline(always)]
    fn fixed<const N: usize, const PLAIN: bool>(p: &mut [f64], ep: &[f64], force: &[f64], k: f64) {
        if let (Ok(p), Ok(ep), Ok(force)) = (
            <&mut [f64; N]>::try_from(p),
            <&[f64; N]>::try_from(ep),
            <&[f64; N]>::try_from(force),
        ) {
            closing_array::<N, PLAIN, f64>(p, ep, force, k);
        }
    }
    match p.len() {
        1 => fixed::<1, PLAIN>(p, ep, force, k),
        2 => fixed::<2, PLAIN>(p, ep, force, k),
        3 => fixed::<3, PLAIN>(p, ep, force, k),
        n if n >= DISPATCH_MIN => closing_kick_long(PLAIN, p, ep, force, k),
        _ => closing_kick_body::<PLAIN>(p, ep, force, k),
    }
}

/// [`kick_drift`] with uniform masses on exactly `N` coordinates (all slices of length `N`,
/// which the caller has checked).
#[inline(always)]
fn fixed<const N: usize, const KIND: u8>(
    q: &mut [f64],
    p: &mut [f64],
    eq: &mut [f64],
    ep: &mut [f64],
    force: &[f64],
    kick: f64,
    dm: f64,
) {
    let (Ok(q), Ok(p), Ok(eq), Ok(ep), Ok(force)) = (
        <&mut [f64; N]>::try_from(q),
        <&mut [f64; N]>::try_from(p),
        <&mut [f64; N]>::try_from(eq),
        <&mut [f64; N]>::try_from(ep),
        <&[f64; N]>::try_from(force),
    ) else {
        return;
    };
    fixed_array::<N, KIND, f64>(q, p, eq, ep, force, kick, dm);
}

/// [`fixed`] on arrays of any [`Real`]: `f64`, or members in SIMD lanes (`lanes.rs`), each
/// lane doing the scalar loop's operations.
#[inline(always)]
fn fixed_array<const N: usize, const KIND: u8, R: Real>(
    q: &mut [R; N],
    p: &mut [R; N],
    eq: &mut [R; N],
    ep: &mut [R; N],
    force: &[R; N],
    kick: f64,
    dm: f64,
) {
    let g = dm * kick;
    for i in 0..N {
        update::<KIND, R>(
            &mut q[i], &mut p[i], &mut eq[i], &mut ep[i], force[i], kick, dm, g,
        );
    }
}

/// The closing kick of [`closing_kick`] on arrays of any [`Real`], as [`fixed_array`].
#[inline(always)]
fn closing_array<const N: usize, const PLAIN: bool, R: Real>(
    p: &mut [R; N],
    ep: &[R; N],
    force: &[R; N],
    k: f64,
) {
    for i in 0..N {
        close::<PLAIN, R>(&mut p[i], ep[i], force[i], k);
    }
}

/// [`substep`] on `N` coordinates held in arrays of any [`Real`] with uniform inverse mass
/// folded into `dm = drift m`: the same update kinds, chosen by the same [`with_pass_kind!`],
/// through the same [`fixed_array`] as the scalar path's fixed-length copies.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn substep_array<const S: usize, const N: usize, R: Real>(
    i: usize,
    q: &mut [R; N],
    p: &mut [R; N],
    eq: &mut [R; N],
    ep: &mut [R; N],
    force: &[R; N],
    kick: f64,
    dm: f64,
) {
    with_pass_kind!(S, i, |KIND| fixed_array::<N, KIND, R>(
        q, p, eq, ep, force, kick, dm
    ));
}

/// [`end_step`] on arrays of any [`Real`].
#[inline(always)]
pub(crate) fn end_step_array<const S: usize, const N: usize, R: Real>(
    p: &mut [R; N],
    ep: &[R; N],
    force: &[R; N],
    k: f64,
) {
    if S <= PLAIN_MAX_DRIFTS {
        closing_array::<N, true, R>(p, ep, force, k);
    } else {
        closing_array::<N, false, R>(p, ep, force, k);
    }
}

#[inline(always)]
fn uniform<const KIND: u8>(
    q: &mut [f64],
    p: &mut [f64],
    eq: &mut [f64],
    ep: &mut [f64],
    force: &[f64],
    kick: f64,
    dm: f64,
) {
    let g = dm * kick;
    for ((((qi, pi), eqi), epi), fi) in q
        .iter_mut()
        .zip(p.iter_mut())
        .zip(eq.iter_mut())
        .zip(ep.iter_mut())
        .zip(force)
    {
        update::<KIND, _>(qi, pi, eqi, epi, *fi, kick, dm, g);
    }
}

#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn per_coordinate<const KIND: u8>(
    q: &mut [f64],
    p: &mut [f64],
    eq: &mut [f64],
    ep: &mut [f64],
    force: &[f64],
    m: &[f64],
    kick: f64,
    drift: f64,
) {
    for (((((qi, pi), eqi), epi), fi), mi) in q
        .iter_mut()
        .zip(p.iter_mut())
        .zip(eq.iter_mut())
        .zip(ep.iter_mut())
        .zip(force)
        .zip(m)
    {
        let dm = drift * mi;
        update::<KIND, _>(qi, pi, eqi, epi, *fi, kick, dm, dm * kick);
    }
}

#[inline(always)]
fn closing_kick_body<const PLAIN: bool>(p: &mut [f64], ep: &[f64], force: &[f64], k: f64) {
    for ((pi, epi), fi) in p.iter_mut().zip(ep).zip(force) {
        close::<PLAIN, _>(pi, *epi, *fi, k);
    }
}

// The loops of long slices, compiled for SSE2, AVX2 and AVX-512 and chosen at run time like
// the slice trig (core/trig.rs). `fma` is not enabled: each clone performs the same IEEE
// multiplications and additions, so the results are the same bits on every machine.

#[multiversion(targets("x86_64+avx512f+avx512dq+avx512vl+avx2", "x86_64+avx2"))]
#[allow(clippy::too_many_arguments)]
fn uniform_long(
    kind: u8,
    q: &mut [f64],
    p: &mut [f64],
    eq: &mut [f64],
    ep: &mut [f64],
    force: &[f64],
    kick: f64,
    dm: f64,
) {
    match kind {
        LAST => uniform::<LAST>(q, p, eq, ep, force, kick, dm),
        PLAIN => uniform::<PLAIN>(q, p, eq, ep, force, kick, dm),
        _ => uniform::<MIDDLE>(q, p, eq, ep, force, kick, dm),
    }
}

#[multiversion(targets("x86_64+avx512f+avx512dq+avx512vl+avx2", "x86_64+avx2"))]
#[allow(clippy::too_many_arguments)]
fn per_coordinate_long(
    kind: u8,
    q: &mut [f64],
    p: &mut [f64],
    eq: &mut [f64],
    ep: &mut [f64],
    force: &[f64],
    m: &[f64],
    kick: f64,
    drift: f64,
) {
    match kind {
        LAST => per_coordinate::<LAST>(q, p, eq, ep, force, m, kick, drift),
        PLAIN => per_coordinate::<PLAIN>(q, p, eq, ep, force, m, kick, drift),
        _ => per_coordinate::<MIDDLE>(q, p, eq, ep, force, m, kick, drift),
    }
}

#[multiversion(targets("x86_64+avx512f+avx512dq+avx512vl+avx2", "x86_64+avx2"))]
fn closing_kick_long(plain: bool, p: &mut [f64], ep: &[f64], force: &[f64], k: f64) {
    if plain {
        closing_kick_body::<true>(p, ep, force, k);
    } else {
        closing_kick_body::<false>(p, ep, force, k);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The run-time-dispatched clones (AVX-512 or AVX2 where the CPU has them) and the
    /// fixed-length copies against the same bodies compiled here at the baseline, bit for bit,
    /// with values spanning many binades and non-zero corrections.
    #[test]
    fn every_path_gives_the_same_bits() {
        let value = |i: usize, k: f64| ((i as f64) * k).sin() * 10f64.powi((i % 9) as i32 - 4);
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        for n in [1, 2, 3, DISPATCH_MIN, DISPATCH_MIN + 1, 100, 257] {
            let q: Vec<f64> = (0..n).map(|i| value(i, 0.37)).collect();
            let p: Vec<f64> = (0..n).map(|i| value(i, 1.13)).collect();
            let f: Vec<f64> = (0..n).map(|i| value(i, 2.71)).collect();
            let e: Vec<f64> = (0..n).map(|i| value(i, 0.91) * 1e-17).collect();
            let m: Vec<f64> = (0..n).map(|i| 1.0 + value(i, 0.05).abs()).collect();
            type Kernel<'a> = &'a dyn Fn(&mut [f64], &mut [f64], &mut [f64], &mut [f64]);
            let run = |kernel: Kernel<'_>| {
                let (mut q, mut p, mut eq, mut ep) = (q.clone(), p.clone(), e.clone(), e.clone());
                kernel(&mut q, &mut p, &mut eq, &mut ep);
                (bits(&q), bits(&p), bits(&eq), bits(&ep))
            };
            let uniform_mass = MassInv::Uniform(0.5);
            let masses = MassInv::PerCoordinate(&m);
            // -0.7 * 0.5 = -0.35 exactly, the uniform mass folded into the drift.
            let cases: [(&str, Kernel<'_>, Kernel<'_>); 8] = [
                (
                    "uniform",
                    &|q, p, eq, ep| kick_drift::<MIDDLE>(uniform_mass, q, p, eq, ep, &f, 0.3, -0.7),
                    &|q, p, eq, ep| uniform::<MIDDLE>(q, p, eq, ep, &f, 0.3, -0.35),
                ),
                (
                    "uniform, last drift",
                    &|q, p, eq, ep| kick_drift::<LAST>(uniform_mass, q, p, eq, ep, &f, 0.3, -0.7),
                    &|q, p, eq, ep| uniform::<LAST>(q, p, eq, ep, &f, 0.3, -0.35),
                ),
                (
                    "masses",
                    &|q, p, eq, ep| kick_drift::<MIDDLE>(masses, q, p, eq, ep, &f, 0.3, -0.7),
                    &|q, p, eq, ep| per_coordinate::<MIDDLE>(q, p, eq, ep, &f, &m, 0.3, -0.7),
                ),
                (
                    "masses, last drift",
                    &|q, p, eq, ep| kick_drift::<LAST>(masses, q, p, eq, ep, &f, 0.3, -0.7),
                    &|q, p, eq, ep| per_coordinate::<LAST>(q, p, eq, ep, &f, &m, 0.3, -0.7),
                ),
                (
                    "uniform, plain",
                    &|q, p, eq, ep| kick_drift::<PLAIN>(uniform_mass, q, p, eq, ep, &f, 0.3, -0.7),
                    &|q, p, eq, ep| uniform::<PLAIN>(q, p, eq, ep, &f, 0.3, -0.35),
                ),
                (
                    "masses, plain",
                    &|q, p, eq, ep| kick_drift::<PLAIN>(masses, q, p, eq, ep, &f, 0.3, -0.7),
                    &|q, p, eq, ep| per_coordinate::<PLAIN>(q, p, eq, ep, &f, &m, 0.3, -0.7),
                ),
                (
                    "closing kick",
                    &|_, p, _, ep| closing_kick::<false>(p, ep, &f, 0.3),
                    &|_, p, _, ep| closing_kick_body::<false>(p, ep, &f, 0.3),
                ),
                (
                    "closing kick, plain",
                    &|_, p, _, ep| closing_kick::<true>(p, ep, &f, 0.3),
                    &|_, p, _, ep| closing_kick_body::<true>(p, ep, &f, 0.3),
                ),
            ];
            for (name, dispatched, body) in cases {
                assert_eq!(run(dispatched), run(body), "{name}, n = {n}");
            }
        }
    }

    /// The corrections make a sum of many small increments exact to their own rounding: ten
    /// thousand kicks of 1e-3 onto 1, then the closing kick, land on 11 to within the
    /// increments' representation error (1e4 * |fl(1e-3) - 1e-3| = 2.1e-16) plus one rounding
    /// of 11 (8.9e-16): 1.2e-15. The same kicks through the `PLAIN` kernels must equal the
    /// naive loop `p += 1e-3` bit for bit and be off by more, so that the test sees the
    /// compensation and that plain steps do not compensate.
    #[test]
    fn a_compensated_sum_of_small_kicks_is_exact_to_one_rounding() {
        fn run<const KIND: u8>() -> f64 {
            let (mut q, mut p, mut eq, mut ep) = ([0.0], [1.0], [-0.0], [-0.0]);
            for _ in 0..10_000 {
                kick_drift::<KIND>(
                    MassInv::Uniform(1.0),
                    &mut q,
                    &mut p,
                    &mut eq,
                    &mut ep,
                    &[1e-3],
                    1.0,
                    0.0,
                );
            }
            if KIND == PLAIN {
                closing_kick::<true>(&mut p, &ep, &[0.0], 0.0);
            } else {
                closing_kick::<false>(&mut p, &ep, &[0.0], 0.0);
            }
            p[0]
        }
        let (compensated, plain) = (run::<MIDDLE>(), run::<PLAIN>());
        let naive = (0..10_000).fold(1.0_f64, |p, _| p + 1e-3);
        println!(
            "compensated {:e}, plain {:e}",
            compensated - 11.0,
            plain - 11.0
        );
        assert!(
            (compensated - 11.0).abs() <= 1.2e-15,
            "{:e}",
            compensated - 11.0
        );
        assert_eq!(plain.to_bits(), naive.to_bits());
        assert!((plain - 11.0).abs() > 1.2e-15, "plain {:e}", plain - 11.0);
    }
}
