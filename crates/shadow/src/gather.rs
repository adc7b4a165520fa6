//! Order-preserving parallel filters: the kept items of a slice, gathered without a serial pass.
//!
//! rayon's `collect` of a filtered parallel iterator builds one vector per work item and joins
//! them on the calling thread: a serial copy of everything kept (for an eye pass's 400 000 visible
//! points, tens of megabytes, while the other workers wait). [`gather`] instead counts what each
//! fixed chunk keeps, then lets each chunk copy its items to their place (the counts' prefix
//! sums), both in parallel. The result is the sequential filter's vector, element for element, on
//! any thread count. [`gather_groups`] does the same for every group of a partition at once.

use rayon::prelude::*;

/// Items per parallel work item of [`gather`]: the split depends on this constant only.
const GATHER_CHUNK: usize = 8192;

/// The items of `items` whose index and value `keep` accepts, in their order.
pub fn gather<T: Copy + Send + Sync>(
    items: &[T],
    keep: impl Fn(usize, &T) -> bool + Sync,
) -> Vec<T> {
    let Some(&first) = items.first() else {
        return Vec::new();
    };
    gather_map(items, first, |index, item| {
        keep(index, item).then_some(*item)
    })
}

/// The values `pick(index, item)` gives for the items of `items` it picks (`Some`), in their
/// order: [`gather`] of something made of each kept item, e.g. its index. `fill` only holds the
/// places before they are written.
pub fn gather_map<T: Sync, U: Copy + Send + Sync>(
    items: &[T],
    fill: U,
    pick: impl Fn(usize, &T) -> Option<U> + Sync,
) -> Vec<U> {
    let counts: Vec<usize> = items
        .par_chunks(GATHER_CHUNK)
        .enumerate()
        .map(|(chunk, part)| picked(chunk, part, &pick).count())
        .collect();
    // Filled by the workers (docs/CONVENTIONS.md, "Large buffers"), then overwritten.
    let mut out: Vec<U> = rayon::iter::repeat_n(fill, counts.iter().sum()).collect();
    let places = pieces(&mut out, counts.iter().copied());
    items
        .par_chunks(GATHER_CHUNK)
        .enumerate()
        .zip(places)
        .for_each(|((chunk, part), place)| {
            for (slot, value) in place.iter_mut().zip(picked(chunk, part, &pick)) {
                *slot = value;
            }
        });
    out
}

/// Items grouped by [`gather_groups`]: every group's items, one group after another, in one
/// vector.
#[derive(Clone, Debug, PartialEq)]
pub struct Groups<T> {
    /// Group 0's items in their order, then group 1's, and so on.
    items: Vec<T>,
    /// Each group's length.
    lengths: Vec<usize>,
}

impl<T> Groups<T> {
    /// Each group's items, in group order.
    #[must_use]
    pub fn slices(&self) -> Vec<&[T]> {
        let mut rest = self.items.as_slice();
        self.lengths
            .iter()
            .map(|&length| {
                let (group, tail) = rest.split_at(length);
                rest = tail;
                group
            })
            .collect()
    }
}

/// The items of `items` grouped by `group_of(index, item)`, a group in `0..groups` — [`gather`] of
/// every group at once, in two passes over the items (count, then copy) into one vector.
///
/// # Panics
/// If `group_of` gives a group outside `0..groups`.
pub fn gather_groups<T: Copy + Send + Sync>(
    items: &[T],
    groups: usize,
    group_of: impl Fn(usize, &T) -> usize + Sync,
) -> Groups<T> {
    let Some(&first) = items.first() else {
        return Groups {
            items: Vec::new(),
            lengths: vec![0; groups],
        };
    };
    let group = |index: usize, item: &T| Some(group_of(index, item));
    let counts: Vec<Vec<usize>> = items
        .par_chunks(GATHER_CHUNK)
        .enumerate()
        .map(|(chunk, part)| {
            let mut counts = vec![0; groups];
            picked(chunk, part, &group).for_each(|group| counts[group] += 1);
            counts
        })
        .collect();
    let lengths: Vec<usize> = (0..groups)
        .map(|group| counts.iter().map(|counts| counts[group]).sum())
        .collect();
    // Filled by the workers (docs/CONVENTIONS.md, "Large buffers"), then overwritten.
    let mut out: Vec<T> = rayon::iter::repeat_n(first, items.len()).collect();
    // Each chunk's place in each group: groups one after another, chunks in order within each.
    let chunks = counts.len();
    let group_major = (0..groups).flat_map(|group| counts.iter().map(move |counts| counts[group]));
    let mut places: Vec<Vec<&mut [T]>> = (0..chunks).map(|_| Vec::with_capacity(groups)).collect();
    for (k, place) in pieces(&mut out, group_major).into_iter().enumerate() {
        places[k % chunks].push(place);
    }
    items
        .par_chunks(GATHER_CHUNK)
        .enumerate()
        .zip(places)
        .for_each(|((chunk, part), mut places)| {
            let mut written = vec![0; groups];
            for (item, group) in part.iter().zip(picked(chunk, part, &group)) {
                places[group][written[group]] = *item;
                written[group] += 1;
            }
        });
    Groups {
        items: out,
        lengths,
    }
}

/// `slice` cut into consecutive pieces of the given `lengths` (which sum to at most its length).
fn pieces<T>(mut slice: &mut [T], lengths: impl IntoIterator<Item = usize>) -> Vec<&mut [T]> {
    lengths
        .into_iter()
        .map(|length| {
            let (piece, tail) = std::mem::take(&mut slice).split_at_mut(length);
            slice = tail;
            piece
        })
        .collect()
}

/// What `pick` makes of the items of chunk number `chunk`, `part`, that it picks (by index in
/// the whole slice).
fn picked<'a, T, U>(
    chunk: usize,
    part: &'a [T],
    pick: &'a impl Fn(usize, &T) -> Option<U>,
) -> impl Iterator<Item = U> + 'a {
    let start = chunk * GATHER_CHUNK;
    part.iter()
        .enumerate()
        .filter_map(move |(i, item)| pick(start + i, item))
}

#[cfg(test)]
mod tests {
    use super::{GATHER_CHUNK, gather, gather_groups, gather_map};

    /// A filter by index and value.
    type Keep<'a> = &'a (dyn Fn(usize, &u64) -> bool + Sync);

    /// Sizes around the chunk size.
    const LENGTHS: [usize; 5] = [0, 1, GATHER_CHUNK - 1, GATHER_CHUNK, 3 * GATHER_CHUNK + 17];

    /// `len` scrambled values.
    fn items(len: usize) -> Vec<u64> {
        (0..len as u64)
            .map(|i| i.wrapping_mul(0x9E37_79B9))
            .collect()
    }

    /// The sequential filter's vector, for sizes around the chunk size and filters that keep
    /// nothing, everything, or an uneven share of each chunk.
    #[test]
    fn gather_is_the_sequential_filter() {
        for len in LENGTHS {
            let items = items(len);
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
                let indices: Vec<usize> = (0..len).filter(|&i| keep(i, &items[i])).collect();
                let picked = gather_map(&items, 0, |i, v| keep(i, v).then_some(i));
                assert_eq!(picked, indices, "{len} items' indices");
            }
        }
    }

    /// Every group is the sequential filter of its items, the groups follow one another in order,
    /// and the lengths count them: sizes around the chunk size, one group to five, some empty.
    #[test]
    fn gather_groups_is_each_groups_sequential_filter() {
        for len in LENGTHS {
            let items = items(len);
            for groups in 1..=5usize {
                // Group 0 left empty where there are several; the rest by value and index.
                let group_of = |i: usize, v: &u64| {
                    if groups == 1 {
                        0
                    } else {
                        1 + (usize::try_from(*v % 7).expect("small") + i / GATHER_CHUNK)
                            % (groups - 1)
                    }
                };
                let gathered = gather_groups(&items, groups, group_of);
                let slices = gathered.slices();
                let lengths: Vec<usize> = slices.iter().map(|group| group.len()).collect();
                let grouped = slices.concat();
                assert_eq!(lengths.len(), groups);
                let mut expected = Vec::new();
                for (group, &length) in lengths.iter().enumerate() {
                    let members: Vec<u64> = items
                        .iter()
                        .enumerate()
                        .filter(|&(i, v)| group_of(i, v) == group)
                        .map(|(_, v)| *v)
                        .collect();
                    assert_eq!(length, members.len(), "{len} items, group {group}");
                    expected.extend(members);
                }
                assert_eq!(grouped, expected, "{len} items in {groups} groups");
            }
        }
    }
}
