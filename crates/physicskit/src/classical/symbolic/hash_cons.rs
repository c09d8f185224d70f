//! Hash-consing for the programs built from expressions (a [`Tape`](super::Tape)'s operations,
//! a [`TaylorProgram`](super::TaylorProgram)'s nodes): each distinct operation is appended
//! once, and asking for it again returns the first one's index, so a subexpression shared
//! between outputs is computed once.

use std::collections::HashMap;
use std::hash::Hash;

/// An operation and the key that identifies it (floats by their bits).
pub(super) trait Keyed: Copy {
    type Key: Hash + Eq;
    fn key(self) -> Self::Key;
}

/// A program's operations, each distinct one once.
pub(super) struct HashCons<T: Keyed> {
    /// The operations in the order they were first asked for.
    pub(super) items: Vec<T>,
    seen: HashMap<T::Key, u32>,
}

impl<T: Keyed> HashCons<T> {
    /// Starts from `items` (inputs that are never looked up).
    pub(super) fn new(items: Vec<T>) -> Self {
        Self {
            items,
            seen: HashMap::new(),
        }
    }

    /// The index of `item` in [`items`](Self::items), appending it if it is new, and whether
    /// it was.
    pub(super) fn intern(&mut self, item: T) -> (u32, bool) {
        let key = item.key();
        if let Some(&i) = self.seen.get(&key) {
            return (i, false);
        }
        let i = self.items.len() as u32;
        self.items.push(item);
        self.seen.insert(key, i);
        (i, true)
    }
}
