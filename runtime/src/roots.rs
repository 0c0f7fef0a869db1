//! Fixed-capacity root containers and the classification every locus intersection returns.
//!
//! Solve paths allocate nothing, so an intersection returns at most `N` roots inline. Slot `i`
//! of [`Roots`] is the root of branch `i`: the branch index is the slot, and each intersection
//! function documents what that index *means* geometrically (which side of a directed line,
//! which order along a direction), so that a fixed branch is followed continuously.

/// At most `N` values of `T`, stored inline. Slot `i` holds the root of branch `i`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Roots<T, const N: usize> {
    len: usize,
    items: [T; N],
}

impl<T: Copy + Default, const N: usize> Default for Roots<T, N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<T: Copy + Default, const N: usize> Roots<T, N> {
    /// No roots.
    #[inline]
    pub fn new() -> Self {
        Self {
            len: 0,
            items: [T::default(); N],
        }
    }

    /// Roots from a slice; values past the capacity `N` are ignored (callers never pass more).
    #[inline]
    pub fn from_slice(values: &[T]) -> Self {
        let mut r = Self::new();
        for &v in values {
            r.push(v);
        }
        r
    }

    /// Appends a root as the next branch. Returns `false`, storing nothing, when full.
    #[inline]
    pub fn push(&mut self, value: T) -> bool {
        if self.len < N {
            self.items[self.len] = value;
            self.len += 1;
            true
        } else {
            false
        }
    }

    /// The number of roots.
    #[inline]
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether there is no root.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The root of branch `index`, if that branch exists.
    #[inline]
    pub fn get(&self, index: usize) -> Option<T> {
        self.as_slice().get(index).copied()
    }

    /// The roots in branch order.
    #[inline]
    pub fn as_slice(&self) -> &[T] {
        &self.items[..self.len]
    }

    /// Keeps only the roots for which `keep` is true, preserving their order.
    #[inline]
    pub fn retain(&mut self, mut keep: impl FnMut(&T) -> bool) {
        let mut w = 0;
        for i in 0..self.len {
            if keep(&self.items[i]) {
                self.items[w] = self.items[i];
                w += 1;
            }
        }
        self.len = w;
    }

    /// The index of the root nearest to `reference` by `distance`, for sweeps that follow a
    /// branch among ordered roots. `None` when there is no root.
    #[inline]
    pub fn nearest_to(&self, reference: T, distance: impl Fn(T, T) -> f64) -> Option<usize> {
        let mut best: Option<(usize, f64)> = None;
        for (i, &v) in self.as_slice().iter().enumerate() {
            let d = distance(v, reference);
            if best.is_none_or(|(_, bd)| d < bd) {
                best = Some((i, d));
            }
        }
        best.map(|(i, _)| i)
    }
}

/// How two loci meet: the classification every intersection function returns beside its roots.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Contact {
    /// Finitely many transversal roots; every branch slot is filled.
    Crossing,
    /// The loci touch: the double root is returned in every branch slot it merges, so a fixed
    /// branch stays defined (and continuous) through the tangency.
    Tangent,
    /// The loci do not meet. `gap` is the smallest distance by which they miss (the magnitude of
    /// the violation an error reports); no roots.
    Disjoint {
        /// Distance between the loci at their closest approach, in length units.
        gap: f64,
    },
    /// The loci are parallel and distinct (lines, planes, a line along a cylinder): no roots.
    Parallel {
        /// Distance between them.
        gap: f64,
    },
    /// The loci coincide on a set of positive dimension: infinitely many roots, none returned.
    Coincident,
    /// An input locus has zero size (a circle or sphere of radius zero, a zero direction); the
    /// function documents whether it then treats it as a point or refuses.
    ZeroRadius,
}

/// The roots of an intersection together with how the loci meet.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Intersection<T, const N: usize> {
    /// The roots, slot `i` being branch `i`.
    pub roots: Roots<T, N>,
    /// The classification of the meeting.
    pub contact: Contact,
}

impl<T: Copy + Default, const N: usize> Intersection<T, N> {
    /// An intersection with no roots.
    #[inline]
    pub fn none(contact: Contact) -> Self {
        Self {
            roots: Roots::new(),
            contact,
        }
    }

    /// The root of branch `index`.
    #[inline]
    pub fn branch(&self, index: usize) -> Option<T> {
        self.roots.get(index)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn roots_hold_at_most_capacity_in_order() {
        let mut r: Roots<f64, 2> = Roots::new();
        assert!(r.push(1.0));
        assert!(r.push(2.0));
        assert!(!r.push(3.0));
        assert_eq!(r.as_slice(), &[1.0, 2.0]);
        assert_eq!(r.get(1), Some(2.0));
        assert_eq!(r.get(2), None);
        assert_eq!(r.nearest_to(1.8, |a, b| (a - b).abs()), Some(1));
        r.retain(|&x| x > 1.5);
        assert_eq!(r.as_slice(), &[2.0]);
    }
}
