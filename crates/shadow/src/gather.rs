//! Order-preserving parallel filters: the kept items of a slice, gathered without a serial pass.
//!
//! rayon's `collect` of a filtered parallel iterator builds one vector per work item and joins
//! them on the calling thread: a serial copy of everything kept (for an eye pass's 400 000 visible
//! points, tens of megabytes, while the other workers wait). [`gather`] instead counts what each
//! fixed chunk keeps, then lets each chunk copy its items to their place (the counts' prefix
//! sums), both in parallel. The result is the sequential filter's vector, element for element, on
//! any thread count.

use rayon::prelude::*;

/// Items per parallel work item of [`gather`]: the split depends on this constant only.
const GATHER_CHUNK: usize = 8192;

/// The items of `items` whose index and value `keep` accepts, in their order.
pub(crate) fn gather<T: Copy + Send + Sync>(
    items: &[T],
    keep: impl Fn(usize, &T) -> bool + Sync,
) -> Vec<T> {
    let counts: Vec<usize> = items
        .par_chunks(GATHER_CHUNK)
        .enumerate()
        .map(|(chunk, part)| kept(chunk, part, &keep).count())
        .collect();
    let Some(&first) = items.first() else {
        return Vec::new();
    };
    // Filled by the workers (docs/CONVENTIONS.md, "Large buffers"), then overwritten.
    let mut out: Vec<T> = rayon::iter::repeat_n(first, counts.iter().sum()).collect();
    let mut places = Vec::with_capacity(counts.len());
    let mut rest = out.as_mut_slice();
    for &count in &counts {
        let (place, tail) = std::mem::take(&mut rest).split_at_mut(count);
        places.push(place);
        rest = tail;
    }
    items
        .par_chunks(GATHER_CHUNK)
        .enumerate()
        .zip(places)
        .for_each(|((chunk, part), place)| {
            for (slot, item) in place.iter_mut().zip(kept(chunk, part, &keep)) {
                *slot = item;
            }
        });
    out
}

/// The items of chunk number `chunk`, `part`, that `keep` accepts (by index in the whole slice).
fn kept<'a, T: Copy>(
    chunk: usize,
    part: &'a [T],
    keep: &'a impl Fn(usize, &T) -> bool,
) -> impl Iterator<Item = T> + 'a {
    let start = chunk * GATHER_CHUNK;
    part.iter()
        .enumerate()
        .filter(move |&(i, item)| keep(start + i, item))
        .map(|(_, item)| *item)
}

#[cfg(test)]
mod tests {
    use super::{GATHER_CHUNK, gather};

    /// A filter by index and value.
    type Keep<'a> = &'a (dyn Fn(usize, &u64) -> bool + Sync);

    /// The sequential filter's vector, for sizes around the chunk size and filters that keep
    /// nothing, everything, or an uneven share of each chunk.
    #[test]
    fn gather_is_the_sequential_filter() {
        for len in [0, 1, GATHER_CHUNK - 1, GATHER_CHUNK, 3 * GATHER_CHUNK + 17] {
            let items: Vec<u64> = (0..len as u64)
                .map(|i| i.wrapping_mul(0x9E37_79B9))
                .collect();
            let filters: [Keep<'_>; 4] =
                [&|_, _| false, &|_, _| true, &|_, v| v % 3 == 0, &|i, _| {
                    i < GATHER_CHUNK / 2 || i % 7 == 1
                }];
            for keep in filters {
                let expected: Vec<u64> = items
                    .iter()
                    .enumerate()
                    .filter(|&(i, v)| keep(i, v))
                    .map(|(_, v)| *v)
                    .collect();
                assert_eq!(gather(&items, keep), expected, "{len} items");
            }
        }
    }
}
