//! Fixed-size forward-mode dual numbers over `f64` on plain arrays, for the engine's
//! single-evaluation kernels (`ndof <= 3`).
//!
//! Three number types, each a truncated Taylor expansion of a value in a few seed directions:
//!
//! ```text
//! DualArr<N>        x + sum_i eps_i e_i                                 (e_i e_j = 0)
//! Dual2Arr<N>       x + sum_i v1_i e_i + sum_ij v2_ij e_i e_j / 2       (third order = 0)
//! HyperArr<A, B>    x + sum_i e1_i a_i + sum_j e2_j b_j + sum_ij e12_ij a_i b_j
//!                   (a_i a_k = b_j b_l = 0)
//! ```
//!
//! They carry the same parts as num-dual's `DualSVec64`, `Dual2SVec64` and `HyperDualSVec64`
//! and implement [`DualNum`] with the same product, quotient and chain rules (Fike & Alonso,
//! AIAA 2011-886), term by term in the same order, so every derivative is bit-for-bit the one
//! num-dual computes for finite values. The difference is the storage: num-dual keeps each
//! derivative part in an `Option` of an nalgebra matrix (a branch and a generic matrix kernel
//! per operation), these keep plain `[f64; N]` arrays that the compiler unrolls, so a product
//! of two `HyperArr<2, 5>` is a few dozen straight-line multiply-adds. The engine built with
//! the `num-dual-kernels` feature uses num-dual's types instead; `benchmarks/README.md`
//! ("Hand-written dual numbers vs num-dual") holds the instruction counts of both.

use std::fmt;
use std::iter::{Product, Sum};
use std::ops::{
    Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Rem, RemAssign, Sub, SubAssign,
};

use num_dual::{DualNum, DualStruct, Mappable};
use num_traits::{FromPrimitive, Inv, Num, One, Signed, Zero};

/// First-order dual vector: value and gradient in `N` directions.
#[derive(Clone, Copy, Debug)]
pub(crate) struct DualArr<const N: usize> {
    pub(crate) re: f64,
    pub(crate) eps: [f64; N],
    /// All derivative parts are zero (a constant), known without reading them.
    c: bool,
}

/// Second-order dual vector: value, gradient and Hessian in `N` directions.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Dual2Arr<const N: usize> {
    pub(crate) re: f64,
    pub(crate) v1: [f64; N],
    pub(crate) v2: [[f64; N]; N],
    /// All derivative parts are zero (a constant).
    c: bool,
}

/// Hyper-dual vector: value, gradients in `A` and in `B` directions, and the `A x B` mixed
/// second derivatives.
#[derive(Clone, Copy, Debug)]
pub(crate) struct HyperArr<const A: usize, const B: usize> {
    pub(crate) re: f64,
    pub(crate) e1: [f64; A],
    pub(crate) e2: [f64; B],
    pub(crate) e12: [[f64; B]; A],
    /// All derivative parts are zero (a constant).
    c: bool,
    /// `e1` and `e12` are zero (independent of the first kind of direction).
    n1: bool,
}

// Plain loops rather than `std::array::from_fn`, whose closure wrapper is not always inlined.
#[inline(always)]
fn map<const N: usize>(x: &[f64; N], f: impl Fn(f64) -> f64) -> [f64; N] {
    let mut r = [0.0; N];
    for (ri, &xi) in r.iter_mut().zip(x) {
        *ri = f(xi);
    }
    r
}

#[inline(always)]
fn zip<const N: usize>(x: &[f64; N], y: &[f64; N], f: impl Fn(f64, f64) -> f64) -> [f64; N] {
    let mut r = [0.0; N];
    for ((ri, &xi), &yi) in r.iter_mut().zip(x).zip(y) {
        *ri = f(xi, yi);
    }
    r
}

#[inline(always)]
fn map2<const A: usize, const B: usize>(
    x: &[[f64; B]; A],
    f: impl Fn(usize, usize, f64) -> f64,
) -> [[f64; B]; A] {
    let mut r = [[0.0; B]; A];
    for (i, (ri, xi)) in r.iter_mut().zip(x).enumerate() {
        for (j, (rij, &xij)) in ri.iter_mut().zip(xi).enumerate() {
            *rij = f(i, j, xij);
        }
    }
    r
}

impl<const N: usize> DualArr<N> {
    #[inline(always)]
    pub(crate) fn from_re(re: f64) -> Self {
        Self {
            re,
            eps: [0.0; N],
            c: true,
        }
    }

    /// `x` seeded in direction `index`.
    #[inline(always)]
    pub(crate) fn seeded(re: f64, index: usize) -> Self {
        let mut d = Self::from_re(re);
        d.eps[index] = 1.0;
        d.c = false;
        d
    }

    #[inline(always)]
    fn map_parts(&self, f: impl Fn(f64) -> f64) -> Self {
        if self.c {
            return Self::from_re(f(self.re));
        }
        Self {
            re: f(self.re),
            eps: map(&self.eps, f),
            c: false,
        }
    }

    #[inline(always)]
    fn zip_parts(&self, o: &Self, f: impl Fn(f64, f64) -> f64) -> Self {
        if self.c && o.c {
            return Self::from_re(f(self.re, o.re));
        }
        Self {
            re: f(self.re, o.re),
            eps: zip(&self.eps, &o.eps, f),
            c: false,
        }
    }

    #[inline(always)]
    fn mul_(&self, o: &Self) -> Self {
        if self.c && o.c {
            return Self::from_re(self.re * o.re);
        }
        Self {
            re: self.re * o.re,
            eps: zip(&self.eps, &o.eps, |a, b| a * o.re + b * self.re),
            c: false,
        }
    }

    #[inline(always)]
    fn div_(&self, o: &Self) -> Self {
        let inv = o.re.recip();
        if self.c && o.c {
            return Self::from_re(self.re * inv);
        }
        Self {
            re: self.re * inv,
            eps: zip(&self.eps, &o.eps, |a, b| {
                (a * o.re - b * self.re) * inv * inv
            }),
            c: false,
        }
    }

    #[inline(always)]
    fn chain(&self, f0: f64, f1: f64, _f2: f64) -> Self {
        if self.c {
            return Self::from_re(f0);
        }
        Self {
            re: f0,
            eps: map(&self.eps, |e| e * f1),
            c: false,
        }
    }

    #[inline(always)]
    fn is_const(&self) -> bool {
        self.c
    }
}

impl<const N: usize> Dual2Arr<N> {
    #[inline(always)]
    pub(crate) fn from_re(re: f64) -> Self {
        Self {
            re,
            v1: [0.0; N],
            v2: [[0.0; N]; N],
            c: true,
        }
    }

    /// `x` seeded in direction `index`.
    #[inline(always)]
    pub(crate) fn seeded(re: f64, index: usize) -> Self {
        let mut d = Self::from_re(re);
        d.v1[index] = 1.0;
        d.c = false;
        d
    }

    #[inline(always)]
    fn map_parts(&self, f: impl Fn(f64) -> f64) -> Self {
        if self.c {
            return Self::from_re(f(self.re));
        }
        Self {
            re: f(self.re),
            v1: map(&self.v1, &f),
            v2: map2(&self.v2, |_, _, x| f(x)),
            c: false,
        }
    }

    #[inline(always)]
    fn zip_parts(&self, o: &Self, f: impl Fn(f64, f64) -> f64) -> Self {
        if self.c && o.c {
            return Self::from_re(f(self.re, o.re));
        }
        Self {
            re: f(self.re, o.re),
            v1: zip(&self.v1, &o.v1, &f),
            v2: map2(&self.v2, |i, j, x| f(x, o.v2[i][j])),
            c: false,
        }
    }

    #[inline(always)]
    fn is_const(&self) -> bool {
        self.c
    }

    #[inline(always)]
    fn mul_(&self, o: &Self) -> Self {
        let (a, b) = (self, o);
        // A constant factor scales the other's parts: the terms num-dual drops are exact zeros.
        if a.c {
            return b.map_parts(|x| x * a.re);
        }
        if b.c {
            return a.map_parts(|x| x * b.re);
        }
        Self {
            c: false,
            re: a.re * b.re,
            v1: zip(&a.v1, &b.v1, |x, y| y * a.re + x * b.re),
            v2: map2(&a.v2, |i, j, x| {
                b.v2[i][j] * a.re + a.v1[i] * b.v1[j] + b.v1[i] * a.v1[j] + x * b.re
            }),
        }
    }

    #[inline(always)]
    fn div_(&self, o: &Self) -> Self {
        let (a, b) = (self, o);
        let inv = b.re.recip();
        let inv2 = inv * inv;
        if a.c && b.c {
            return Self::from_re(a.re * inv);
        }
        let c = 2.0 * a.re * inv2 * inv;
        Self {
            c: false,
            re: a.re * inv,
            v1: zip(&a.v1, &b.v1, |x, y| (x * b.re - y * a.re) * inv2),
            v2: map2(&a.v2, |i, j, x| {
                x * inv - (b.v2[i][j] * a.re + a.v1[i] * b.v1[j] + b.v1[i] * a.v1[j]) * inv2
                    + b.v1[i] * b.v1[j] * c
            }),
        }
    }

    #[inline(always)]
    fn chain(&self, f0: f64, f1: f64, f2: f64) -> Self {
        if self.c {
            return Self::from_re(f0);
        }
        Self {
            c: false,
            re: f0,
            v1: map(&self.v1, |e| e * f1),
            v2: map2(&self.v2, |i, j, x| x * f1 + self.v1[i] * self.v1[j] * f2),
        }
    }
}

impl<const A: usize, const B: usize> HyperArr<A, B> {
    #[inline(always)]
    pub(crate) fn from_re(re: f64) -> Self {
        Self {
            re,
            e1: [0.0; A],
            e2: [0.0; B],
            e12: [[0.0; B]; A],
            c: true,
            n1: true,
        }
    }

    /// `x` with derivative 1 in direction `index` of the first kind (`e1`).
    #[inline(always)]
    pub(crate) fn derivative1(mut self, index: usize) -> Self {
        self.e1[index] = 1.0;
        self.c = false;
        self.n1 = false;
        self
    }

    /// `x` with derivative 1 in direction `index` of the second kind (`e2`).
    #[inline(always)]
    pub(crate) fn derivative2(mut self, index: usize) -> Self {
        self.e2[index] = 1.0;
        self.c = false;
        self
    }

    /// Value and `e2` part only (`e1`, `e12` zero).
    #[inline(always)]
    fn only2(re: f64, e2: [f64; B]) -> Self {
        Self {
            re,
            e1: [0.0; A],
            e2,
            e12: [[0.0; B]; A],
            c: false,
            n1: true,
        }
    }

    #[inline(always)]
    fn is_const(&self) -> bool {
        self.c
    }

    #[inline(always)]
    fn map_parts(&self, f: impl Fn(f64) -> f64) -> Self {
        if self.c {
            return Self::from_re(f(self.re));
        }
        if self.n1 {
            return Self::only2(f(self.re), map(&self.e2, &f));
        }
        Self {
            re: f(self.re),
            e1: map(&self.e1, &f),
            e2: map(&self.e2, &f),
            e12: map2(&self.e12, |_, _, x| f(x)),
            c: false,
            n1: false,
        }
    }

    #[inline(always)]
    fn zip_parts(&self, o: &Self, f: impl Fn(f64, f64) -> f64) -> Self {
        if self.c && o.c {
            return Self::from_re(f(self.re, o.re));
        }
        if self.n1 && o.n1 {
            return Self::only2(f(self.re, o.re), zip(&self.e2, &o.e2, &f));
        }
        Self {
            re: f(self.re, o.re),
            e1: zip(&self.e1, &o.e1, &f),
            e2: zip(&self.e2, &o.e2, &f),
            e12: map2(&self.e12, |i, j, x| f(x, o.e12[i][j])),
            c: false,
            n1: false,
        }
    }

    #[inline(always)]
    fn mul_(&self, o: &Self) -> Self {
        let (a, b) = (self, o);
        // A constant factor scales the other's parts: the terms num-dual drops are exact zeros.
        if a.c {
            return b.map_parts(|x| x * a.re);
        }
        if b.c {
            return a.map_parts(|x| x * b.re);
        }
        if a.n1 && b.n1 {
            return Self::only2(a.re * b.re, zip(&a.e2, &b.e2, |x, y| y * a.re + x * b.re));
        }
        Self {
            c: false,
            n1: false,
            re: a.re * b.re,
            e1: zip(&a.e1, &b.e1, |x, y| y * a.re + x * b.re),
            e2: zip(&a.e2, &b.e2, |x, y| y * a.re + x * b.re),
            e12: map2(&a.e12, |i, j, x| {
                b.e12[i][j] * a.re + a.e1[i] * b.e2[j] + b.e1[i] * a.e2[j] + x * b.re
            }),
        }
    }

    #[inline(always)]
    fn div_(&self, o: &Self) -> Self {
        let (a, b) = (self, o);
        let inv = b.re.recip();
        let inv2 = inv * inv;
        if a.c && b.c {
            return Self::from_re(a.re * inv);
        }
        let c = 2.0 * a.re * inv2 * inv;
        Self {
            c: false,
            n1: false,
            re: a.re * inv,
            e1: zip(&a.e1, &b.e1, |x, y| (x * b.re - y * a.re) * inv2),
            e2: zip(&a.e2, &b.e2, |x, y| (x * b.re - y * a.re) * inv2),
            e12: map2(&a.e12, |i, j, x| {
                x * inv - (b.e12[i][j] * a.re + a.e1[i] * b.e2[j] + b.e1[i] * a.e2[j]) * inv2
                    + b.e1[i] * b.e2[j] * c
            }),
        }
    }

    #[inline(always)]
    fn chain(&self, f0: f64, f1: f64, f2: f64) -> Self {
        if self.c {
            return Self::from_re(f0);
        }
        if self.n1 {
            return Self::only2(f0, map(&self.e2, |e| e * f1));
        }
        Self {
            c: false,
            n1: false,
            re: f0,
            e1: map(&self.e1, |e| e * f1),
            e2: map(&self.e2, |e| e * f1),
            e12: map2(&self.e12, |i, j, x| x * f1 + self.e1[i] * self.e2[j] * f2),
        }
    }
}

/// Everything [`DualNum`] asks of a number type, from the inherent `from_re`, `map_parts`,
/// `zip_parts`, `mul_`, `div_` and `chain` (value, first and second derivative of a scalar
/// function) of each type.
macro_rules! impl_dual_arr {
    ([$($g:tt)*] $t:ty) => {
        impl<$($g)*> From<f64> for $t {
            #[inline(always)]
            fn from(x: f64) -> Self {
                Self::from_re(x)
            }
        }

        impl<$($g)*> Zero for $t {
            #[inline(always)]
            fn zero() -> Self {
                Self::from_re(0.0)
            }
            #[inline(always)]
            fn is_zero(&self) -> bool {
                self.re == 0.0
            }
        }

        impl<$($g)*> One for $t {
            #[inline(always)]
            fn one() -> Self {
                Self::from_re(1.0)
            }
            #[inline(always)]
            fn is_one(&self) -> bool {
                self.re.is_one()
            }
        }

        impl_dual_arr!(@binop [$($g)*] $t, Add, add, |a: &$t, b: &$t| a.zip_parts(b, |x, y| x + y));
        impl_dual_arr!(@binop [$($g)*] $t, Sub, sub, |a: &$t, b: &$t| a.zip_parts(b, |x, y| x - y));
        impl_dual_arr!(@binop [$($g)*] $t, Mul, mul, |a: &$t, b: &$t| a.mul_(b));
        impl_dual_arr!(@binop [$($g)*] $t, Div, div, |a: &$t, b: &$t| a.div_(b));
        impl_dual_arr!(@binop [$($g)*] $t, Rem, rem, |_a: &$t, _b: &$t| -> $t {
            unimplemented!("remainder of dual numbers")
        });

        impl<$($g)*> Neg for $t {
            type Output = Self;
            #[inline(always)]
            fn neg(self) -> Self {
                self.map_parts(|x| -x)
            }
        }

        impl<$($g)*> Neg for &$t {
            type Output = $t;
            #[inline(always)]
            fn neg(self) -> $t {
                self.map_parts(|x| -x)
            }
        }

        impl<$($g)*> AddAssign for $t {
            #[inline(always)]
            fn add_assign(&mut self, o: Self) {
                *self = *self + o;
            }
        }
        impl<$($g)*> SubAssign for $t {
            #[inline(always)]
            fn sub_assign(&mut self, o: Self) {
                *self = *self - o;
            }
        }
        impl<$($g)*> MulAssign for $t {
            #[inline(always)]
            fn mul_assign(&mut self, o: Self) {
                *self = *self * o;
            }
        }
        impl<$($g)*> DivAssign for $t {
            #[inline(always)]
            fn div_assign(&mut self, o: Self) {
                *self = *self / o;
            }
        }
        impl<$($g)*> RemAssign for $t {
            fn rem_assign(&mut self, _o: Self) {
                unimplemented!("remainder of dual numbers")
            }
        }

        impl<$($g)*> Mul<f64> for $t {
            type Output = Self;
            #[inline(always)]
            fn mul(self, o: f64) -> Self {
                self.map_parts(|x| x * o)
            }
        }
        impl<$($g)*> MulAssign<f64> for $t {
            #[inline(always)]
            fn mul_assign(&mut self, o: f64) {
                *self = *self * o;
            }
        }
        impl<$($g)*> Div<f64> for $t {
            type Output = Self;
            #[inline(always)]
            fn div(self, o: f64) -> Self {
                self.map_parts(|x| x / o)
            }
        }
        impl<$($g)*> DivAssign<f64> for $t {
            #[inline(always)]
            fn div_assign(&mut self, o: f64) {
                *self = *self / o;
            }
        }
        impl<$($g)*> Add<f64> for $t {
            type Output = Self;
            #[inline(always)]
            fn add(mut self, o: f64) -> Self {
                self.re += o;
                self
            }
        }
        impl<$($g)*> AddAssign<f64> for $t {
            #[inline(always)]
            fn add_assign(&mut self, o: f64) {
                self.re += o;
            }
        }
        impl<$($g)*> Sub<f64> for $t {
            type Output = Self;
            #[inline(always)]
            fn sub(mut self, o: f64) -> Self {
                self.re -= o;
                self
            }
        }
        impl<$($g)*> SubAssign<f64> for $t {
            #[inline(always)]
            fn sub_assign(&mut self, o: f64) {
                self.re -= o;
            }
        }
        impl<$($g)*> Rem<f64> for $t {
            type Output = Self;
            fn rem(self, _o: f64) -> Self {
                unimplemented!("remainder of dual numbers")
            }
        }
        impl<$($g)*> RemAssign<f64> for $t {
            fn rem_assign(&mut self, _o: f64) {
                unimplemented!("remainder of dual numbers")
            }
        }

        impl<$($g)*> Inv for $t {
            type Output = Self;
            #[inline(always)]
            fn inv(self) -> Self {
                self.recip()
            }
        }

        impl<$($g)*> Sum for $t {
            fn sum<I: Iterator<Item = Self>>(iter: I) -> Self {
                iter.fold(Self::zero(), |acc, c| acc + c)
            }
        }
        impl<'a, $($g)*> Sum<&'a $t> for $t {
            fn sum<I: Iterator<Item = &'a $t>>(iter: I) -> Self {
                iter.fold(Self::zero(), |acc, c| acc + c)
            }
        }
        impl<$($g)*> Product for $t {
            fn product<I: Iterator<Item = Self>>(iter: I) -> Self {
                iter.fold(Self::one(), |acc, c| acc * c)
            }
        }
        impl<'a, $($g)*> Product<&'a $t> for $t {
            fn product<I: Iterator<Item = &'a $t>>(iter: I) -> Self {
                iter.fold(Self::one(), |acc, c| acc * c)
            }
        }

        impl<$($g)*> FromPrimitive for $t {
            fn from_i64(n: i64) -> Option<Self> {
                f64::from_i64(n).map(Self::from_re)
            }
            fn from_u64(n: u64) -> Option<Self> {
                f64::from_u64(n).map(Self::from_re)
            }
            fn from_f64(n: f64) -> Option<Self> {
                Some(Self::from_re(n))
            }
            fn from_f32(n: f32) -> Option<Self> {
                Some(Self::from_re(f64::from(n)))
            }
        }

        impl<$($g)*> Num for $t {
            type FromStrRadixErr = <f64 as Num>::FromStrRadixErr;
            fn from_str_radix(s: &str, radix: u32) -> Result<Self, Self::FromStrRadixErr> {
                f64::from_str_radix(s, radix).map(Self::from_re)
            }
        }

        impl<$($g)*> Signed for $t {
            fn abs(&self) -> Self {
                if self.is_positive() {
                    *self
                } else {
                    -self
                }
            }
            fn abs_sub(&self, other: &Self) -> Self {
                if self.re > other.re {
                    self - other
                } else {
                    Self::zero()
                }
            }
            fn signum(&self) -> Self {
                if self.is_positive() {
                    Self::one()
                } else if self.is_zero() {
                    Self::zero()
                } else {
                    -Self::one()
                }
            }
            fn is_positive(&self) -> bool {
                self.re.is_sign_positive()
            }
            fn is_negative(&self) -> bool {
                self.re.is_sign_negative()
            }
        }

        impl<$($g)*> DualStruct for $t {
            type Real = f64;
            type Inner = f64;
            #[inline(always)]
            fn re(&self) -> f64 {
                self.re
            }
            #[inline(always)]
            fn from_inner(inner: &f64) -> Self {
                Self::from_re(*inner)
            }
        }

        impl<$($g)*> Mappable<Self> for $t {
            type Output<O> = O;
            fn map_dual<G: Fn(Self) -> O, O>(self, g: G) -> O {
                g(self)
            }
        }

        impl<$($g)*> PartialEq for $t {
            fn eq(&self, other: &Self) -> bool {
                self.re == other.re
            }
        }
        impl<$($g)*> PartialEq<f64> for $t {
            fn eq(&self, other: &f64) -> bool {
                self.re == *other
            }
        }
        impl<$($g)*> PartialOrd for $t {
            fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
                self.re.partial_cmp(&other.re)
            }
        }
        impl<$($g)*> PartialOrd<f64> for $t {
            fn partial_cmp(&self, other: &f64) -> Option<std::cmp::Ordering> {
                self.re.partial_cmp(other)
            }
        }

        impl<$($g)*> fmt::Display for $t {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, "{} + {:?}", self.re, self)
            }
        }

        impl<$($g)*> DualNum for $t {
            type Primitive = f64;
            const NDERIV: usize = 2;
            type InnerDual = f64;

            #[inline(always)]
            fn from_re(re: f64) -> Self {
                Self::from_re(re)
            }

            #[inline(always)]
            fn scale(self, factor: &f64) -> Self {
                self.map_parts(|x| x * factor)
            }

            #[inline(always)]
            fn recip(&self) -> Self {
                let rec = self.re.recip();
                let f1 = -rec * rec;
                let f2 = -f1 * rec * 2.0;
                self.chain(rec, f1, f2)
            }

            #[inline(always)]
            fn powi(&self, exp: i32) -> Self {
                match exp {
                    0 => Self::one(),
                    1 => *self,
                    2 => self * self,
                    _ => {
                        let r = self.re;
                        let pow3 = r.powi(exp - 3);
                        let f0 = pow3 * r * r * r;
                        let f1 = pow3 * r * r * f64::from(exp);
                        let f2 = pow3 * r * f64::from(exp * (exp - 1));
                        self.chain(f0, f1, f2)
                    }
                }
            }

            #[inline(always)]
            fn powf(&self, n: f64) -> Self {
                if n == 0.0 {
                    Self::one()
                } else if n.is_one() {
                    *self
                } else if (n - 1.0 - 1.0).abs() < f64::EPSILON {
                    self * self
                } else {
                    let r = self.re;
                    let n1 = n - 1.0;
                    let n3 = n1 - 1.0 - 1.0;
                    let pow3 = r.powf(n3);
                    let f0 = pow3 * r * r * r;
                    let f1 = pow3 * r * r * n;
                    let f2 = pow3 * r * n * n1;
                    self.chain(f0, f1, f2)
                }
            }

            #[inline(always)]
            fn sqrt(&self) -> Self {
                let rec = self.re.recip();
                let f0 = self.re.sqrt();
                let f1 = f0 * rec * 0.5;
                let f2 = -f1 * rec * 0.5;
                self.chain(f0, f1, f2)
            }

            #[inline(always)]
            fn cbrt(&self) -> Self {
                let rec = self.re.recip();
                let third = 1.0 / 3.0;
                let f0 = self.re.cbrt();
                let f1 = f0 * rec * third;
                let f2 = f1 * rec * (third - 1.0);
                self.chain(f0, f1, f2)
            }

            #[inline(always)]
            fn exp(&self) -> Self {
                let f = self.re.exp();
                self.chain(f, f, f)
            }

            #[inline(always)]
            fn exp2(&self) -> Self {
                let ln2 = 2.0_f64.ln();
                let f0 = self.re.exp2();
                let f1 = f0 * ln2;
                let f2 = f1 * ln2;
                self.chain(f0, f1, f2)
            }

            #[inline(always)]
            fn exp_m1(&self) -> Self {
                let f0 = self.re.exp_m1();
                let f1 = self.re.exp();
                self.chain(f0, f1, f1)
            }

            #[inline(always)]
            fn ln(&self) -> Self {
                let rec = self.re.recip();
                let f2 = -rec * rec;
                self.chain(self.re.ln(), rec, f2)
            }

            #[inline(always)]
            fn log(&self, base: f64) -> Self {
                let rec = self.re.recip();
                let f1 = rec / base.ln();
                let f2 = -f1 * rec;
                self.chain(self.re.log(base), f1, f2)
            }

            #[inline(always)]
            fn log2(&self) -> Self {
                let rec = self.re.recip();
                let f1 = rec / 2.0_f64.ln();
                let f2 = -f1 * rec;
                self.chain(self.re.log2(), f1, f2)
            }

            #[inline(always)]
            fn log10(&self) -> Self {
                let rec = self.re.recip();
                let f1 = rec / std::f64::consts::LN_10;
                let f2 = -f1 * rec;
                self.chain(self.re.log10(), f1, f2)
            }

            #[inline(always)]
            fn ln_1p(&self) -> Self {
                let rec = (self.re + 1.0).recip();
                let f2 = -rec * rec;
                self.chain(self.re.ln_1p(), rec, f2)
            }

            #[inline(always)]
            fn sin(&self) -> Self {
                if self.is_const() {
                    return Self::from_re(self.re.sin());
                }
                let (s, c) = self.re.sin_cos();
                self.chain(s, c, -s)
            }

            #[inline(always)]
            fn cos(&self) -> Self {
                if self.is_const() {
                    return Self::from_re(self.re.cos());
                }
                let (s, c) = self.re.sin_cos();
                self.chain(c, -s, -c)
            }

            #[inline(always)]
            fn sin_cos(&self) -> (Self, Self) {
                let (s, c) = self.re.sin_cos();
                (self.chain(s, c, -s), self.chain(c, -s, -c))
            }

            #[inline(always)]
            fn tan(&self) -> Self {
                let (s, c) = self.sin_cos();
                s / c
            }

            #[inline(always)]
            fn asin(&self) -> Self {
                let r = self.re;
                let rec = (1.0 - r * r).recip();
                let f1 = rec.sqrt();
                self.chain(r.asin(), f1, r * f1 * rec)
            }

            #[inline(always)]
            fn acos(&self) -> Self {
                let r = self.re;
                let rec = (1.0 - r * r).recip();
                let f1 = -rec.sqrt();
                self.chain(r.acos(), f1, r * f1 * rec)
            }

            #[inline(always)]
            fn atan(&self) -> Self {
                let r = self.re;
                let rec = (1.0 + r * r).recip();
                self.chain(r.atan(), rec, -r * rec * rec * 2.0)
            }

            #[inline(always)]
            fn atan2(&self, other: Self) -> Self {
                let mut res = (self / other).atan();
                res.re = self.re.atan2(other.re);
                res
            }

            #[inline(always)]
            fn sinh(&self) -> Self {
                let (s, c) = (self.re.sinh(), self.re.cosh());
                self.chain(s, c, s)
            }

            #[inline(always)]
            fn cosh(&self) -> Self {
                let (s, c) = (self.re.sinh(), self.re.cosh());
                self.chain(c, s, c)
            }

            #[inline(always)]
            fn tanh(&self) -> Self {
                self.sinh() / self.cosh()
            }

            #[inline(always)]
            fn asinh(&self) -> Self {
                let r = self.re;
                let rec = (1.0 + r * r).recip();
                let f1 = rec.sqrt();
                self.chain(r.asinh(), f1, -r * f1 * rec)
            }

            #[inline(always)]
            fn acosh(&self) -> Self {
                let r = self.re;
                let rec = (r * r - 1.0).recip();
                let f1 = rec.sqrt();
                self.chain(r.acosh(), f1, -r * f1 * rec)
            }

            #[inline(always)]
            fn atanh(&self) -> Self {
                let r = self.re;
                let rec = (1.0 - r * r).recip();
                self.chain(r.atanh(), rec, r * rec * rec * 2.0)
            }

            fn sph_j0(&self) -> Self {
                if self.re.abs() < f64::EPSILON {
                    Self::one() - self * self / 6.0
                } else {
                    self.sin() / self
                }
            }

            fn sph_j1(&self) -> Self {
                if self.re.abs() < f64::EPSILON {
                    *self / 3.0
                } else {
                    let (s, c) = self.sin_cos();
                    (s - self * c) / (self * self)
                }
            }

            fn sph_j2(&self) -> Self {
                if self.re.abs() < f64::EPSILON {
                    self * self / 15.0
                } else {
                    let (s, c) = self.sin_cos();
                    let s2 = self * self;
                    ((s - self * c) * 3.0 - s2 * s) / (s2 * self)
                }
            }
        }
    };
    (@binop [$($g:tt)*] $t:ty, $trt:ident, $m:ident, $f:expr) => {
        impl<$($g)*> $trt<&$t> for &$t {
            type Output = $t;
            #[inline(always)]
            fn $m(self, o: &$t) -> $t {
                ($f)(self, o)
            }
        }
        impl<$($g)*> $trt<$t> for &$t {
            type Output = $t;
            #[inline(always)]
            fn $m(self, o: $t) -> $t {
                ($f)(self, &o)
            }
        }
        impl<$($g)*> $trt<&$t> for $t {
            type Output = $t;
            #[inline(always)]
            fn $m(self, o: &$t) -> $t {
                ($f)(&self, o)
            }
        }
        impl<$($g)*> $trt<$t> for $t {
            type Output = $t;
            #[inline(always)]
            fn $m(self, o: $t) -> $t {
                ($f)(&self, &o)
            }
        }
    };
}

impl_dual_arr!([const N: usize] DualArr<N>);
impl_dual_arr!([const N: usize] Dual2Arr<N>);
impl_dual_arr!([const A: usize, const B: usize] HyperArr<A, B>);

#[cfg(test)]
mod tests {
    use super::*;
    use num_dual::{Dual2_64, Dual64, HyperDual64};

    /// The bits of `v`, with `-0.0` read as `0.0` (num-dual leaves an absent derivative out of
    /// a sum; adding the array types' exact zero can flip the sign of a zero result only).
    fn bits(v: f64) -> u64 {
        (v + 0.0).to_bits()
    }

    /// Every function on the array types against num-dual's scalar types of the same order
    /// (independent implementation): value and derivatives must agree bit for bit, because
    /// the rules and their term order are the same.
    macro_rules! check_all {
        ($x:expr, $y:expr, $($name:literal => |$a:ident, $b:ident| $e:expr),* $(,)?) => {$(
            {
                let (x, y): (f64, f64) = ($x, $y);
                // Seeds: x varies along both directions, y along the second only.
                let h = {
                    let $a = HyperArr::<1, 1>::from_re(x).derivative1(0).derivative2(0);
                    let $b = HyperArr::<1, 1>::from_re(y).derivative2(0);
                    $e
                };
                let hr = {
                    let $a = HyperDual64::new(x, 1.0, 1.0, 0.0);
                    let $b = HyperDual64::new(y, 0.0, 1.0, 0.0);
                    $e
                };
                let got = [h.re, h.e1[0], h.e2[0], h.e12[0][0]];
                let want = [hr.re, hr.eps1, hr.eps2, hr.eps1eps2];
                assert_eq!(got.map(bits), want.map(bits), "hyper {}: {got:?} vs {want:?}", $name);
                let d2 = {
                    let $a = Dual2Arr::<1>::seeded(x, 0);
                    let $b = Dual2Arr::<1>::from_re(y);
                    $e
                };
                let d2r = {
                    let $a = Dual2_64::new(x, 1.0, 0.0);
                    let $b = Dual2_64::new(y, 0.0, 0.0);
                    $e
                };
                let got = [d2.re, d2.v1[0], d2.v2[0][0]];
                let want = [d2r.re, d2r.v1, d2r.v2];
                assert_eq!(got.map(bits), want.map(bits), "dual2 {}: {got:?} vs {want:?}", $name);
                let d = {
                    let $a = DualArr::<2>::seeded(x, 0);
                    let $b = DualArr::<2>::seeded(y, 1);
                    $e
                };
                let dr_x = {
                    let $a = Dual64::new(x, 1.0);
                    let $b = Dual64::new(y, 0.0);
                    $e
                };
                let dr_y = {
                    let $a = Dual64::new(x, 0.0);
                    let $b = Dual64::new(y, 1.0);
                    $e
                };
                let got = [d.re, d.eps[0], d.eps[1]];
                let want = [dr_x.re, dr_x.eps, dr_y.eps];
                assert_eq!(got.map(bits), want.map(bits), "dual {}: {got:?} vs {want:?}", $name);
            }
        )*};
    }

    #[test]
    fn derivatives_match_num_dual_bit_for_bit() {
        for &(x, y) in &[(0.37, 1.9), (-0.61, 2.3), (0.05, -0.8)] {
            check_all!(x, y,
                "add" => |a, b| a + b * 2.0 - 1.5,
                "mul" => |a, b| a * b * a,
                "div" => |a, b| (a * 3.0 + b) / (b * a + 4.0),
                "neg" => |a, b| -(a * b) / 3.0,
                "recip" => |a, b| (a + b * 0.1 + 3.0).recip(),
                "powi" => |a, b| (a * b).powi(3) + a.powi(2) + b.powi(-2),
                "powf" => |a, b| (a * a + b * b).powf(1.7),
                "sqrt" => |a, b| (a * a + b * b).sqrt(),
                "cbrt" => |a, b| (a * b + 5.0).cbrt(),
                "exp" => |a, b| (a * b).exp() + a.exp2() + a.exp_m1(),
                "ln" => |a, b| (a * a + b * b).ln() + (a * a + 1.0).log(3.0),
                "log2" => |a, b| (a * a + b * b).log2() + (a * a + 1.0).log10() + (a * a).ln_1p(),
                "trig" => |a, b| (a * b).sin() * a.cos() + (a + b).tan() + b.sin(),
                "sin_cos" => |a, b| { let (s, c) = (a - b).sin_cos(); s * c * a },
                "inverse trig" => |a, b| (a * 0.5).asin() + (a * 0.5).acos() + (a * b).atan() + a.atan2(b),
                "hyperbolic" => |a, b| (a * b).sinh() + a.cosh() + (a + b).tanh(),
                "inverse hyperbolic" => |a, b| (a * b).asinh() + (a * a + 2.0).acosh() + (a * 0.5).atanh(),
                "bessel" => |a, b| (a * b).sph_j0() + (a * 3.0).sph_j1() + b.sph_j2(),
                "const" => |a, b| b.cos() * b * (b + 1.0).sqrt() + a,
            );
        }
    }
}
