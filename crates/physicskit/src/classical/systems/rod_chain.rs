//! The bobs of a chain of rigid rods hanging from a pivot at the origin (`y` up), each rod at
//! its angle `q_i` from the downward vertical: bob `i` sits at the sum of the rods' vectors
//! `l_j (sin q_j, -cos q_j)`, `j <= i`. The double and triple pendulums draw and report their
//! bobs with it.

use crate::classical::lagrangian::Scalar;

/// Writes the bobs' positions `[x1, y1, x2, y2, ...]` of rods of `lengths` at angles `q` into
/// `out` (two entries per rod), generic over the scalar type (plain `f64`s, or the engine's
/// dual numbers). The first bob is its rod's vector, each later one the previous bob plus its
/// rod's, summed in chain order.
///
/// `q`, `lengths` and the pairs of `out` are walked together: the callers pass one angle and
/// one length per rod and an `out` of twice the rods.
pub(crate) fn rod_chain_positions<X: Scalar>(q: &[X], lengths: &[f64], out: &mut [X]) {
    let mut bob: Option<(X, X)> = None;
    for ((angle, &length), point) in q.iter().zip(lengths).zip(out.chunks_exact_mut(2)) {
        let (s, c) = angle.sin_cos();
        let (x, y) = match bob {
            None => (s * length, -(c * length)),
            Some((x, y)) => (x + s * length, y - c * length),
        };
        point[0] = x;
        point[1] = y;
        bob = Some((x, y));
    }
}
