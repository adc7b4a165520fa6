//! Integer tallies counted in parallel: each fixed chunk of the work counts into a tally of its
//! own, and the chunks' tallies are summed. Integer sums are exact and do not depend on the order
//! of the additions, so the total is the same however rayon splits and joins the chunks — on any
//! thread count.

use std::ops::AddAssign;

use rayon::prelude::*;

/// Items per chunk of a tally counted in parallel. Any size gives the same total: the counts are
/// integers.
pub(crate) const TALLY_CHUNK: usize = 1 << 14;

/// The sum of the chunks' `tallies`.
pub(crate) fn total<T: Default + AddAssign + Send>(tallies: impl ParallelIterator<Item = T>) -> T {
    tallies.reduce(T::default, |mut total, part| {
        total += part;
        total
    })
}
