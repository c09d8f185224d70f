//! Fixed-capacity work buffers that live on the stack for small systems.
//!
//! The engine needs a handful of vectors and `ndof x ndof` matrices per evaluation. Up to
//! [`MAX_STACK_NDOF`] degrees of freedom they are plain arrays on the stack, so an evaluation
//! never touches the heap; above it they fall back to one `Vec` each (the `O(ndof^3)` cost of
//! the evaluation then dwarfs the allocation).

/// Largest number of degrees of freedom whose work buffers live on the stack.
pub const MAX_STACK_NDOF: usize = 8;

/// Capacity of a stack vector buffer.
pub(crate) const VEC_CAP: usize = MAX_STACK_NDOF;

/// Capacity of a stack matrix buffer.
pub(crate) const MAT_CAP: usize = MAX_STACK_NDOF * MAX_STACK_NDOF;

/// `len` values of `T`, on the stack when `len <= N`, else on the heap.
pub(crate) struct SmallBuf<T: Copy, const N: usize> {
    stack: [T; N],
    heap: Vec<T>,
    len: usize,
}

impl<T: Copy, const N: usize> SmallBuf<T, N> {
    /// A buffer of `len` copies of `fill`.
    #[inline]
    pub(crate) fn new(len: usize, fill: T) -> Self {
        let heap = if len > N { vec![fill; len] } else { Vec::new() };
        Self {
            stack: [fill; N],
            heap,
            len,
        }
    }

    /// The values.
    #[inline]
    pub(crate) fn as_slice(&self) -> &[T] {
        if self.len > N {
            &self.heap
        } else {
            &self.stack[..self.len]
        }
    }

    /// The values, mutably.
    #[inline]
    pub(crate) fn as_mut_slice(&mut self) -> &mut [T] {
        if self.len > N {
            &mut self.heap
        } else {
            &mut self.stack[..self.len]
        }
    }
}

/// A vector buffer of `ndof` values.
pub(crate) type VecBuf<T> = SmallBuf<T, VEC_CAP>;

/// A matrix buffer of `ndof * ndof` values.
pub(crate) type MatBuf = SmallBuf<f64, MAT_CAP>;
