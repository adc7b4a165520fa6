//! Shards: which cells each of N independent runs measures. The assignment depends only on the
//! plan and N, so every shard computes the same one without talking to the others.

use std::cmp::Reverse;
use std::collections::{BinaryHeap, HashSet};
use std::fmt;

use crate::cells::Plan;
use crate::error::SweepError;

/// Shard `index` of `count` (`I/N` on the command line, 0-based).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// Which shard, `0..count`.
    pub index: usize,
    /// How many.
    pub count: usize,
}

/// The most shards a sweep may be split into.
pub const MAX_SHARDS: usize = 100_000;

/// A plan with at least this many frames per shard is assigned whole frames (every cell of a
/// frame on one shard, its truth computed once); a smaller one is assigned cell by cell, each
/// shard computing the truth of every frame it has a cell of.
pub const FRAMES_PER_SHARD_TO_KEEP_FRAMES_WHOLE: usize = 4;

impl Shard {
    /// The whole sweep as one shard.
    pub const ALL: Self = Self { index: 0, count: 1 };

    /// Parses `I/N` with `0 ≤ I < N ≤` [`MAX_SHARDS`].
    ///
    /// # Errors
    /// A message naming the form and the range.
    pub fn parse(text: &str) -> Result<Self, String> {
        let bad = || {
            format!(
                "`{text}` is not a shard: give I/N, shard I (0-based) of N, 0 ≤ I < N ≤ {MAX_SHARDS}"
            )
        };
        let (i, n) = text.split_once('/').ok_or_else(bad)?;
        let index: usize = i.trim().parse().map_err(|_| bad())?;
        let count: usize = n.trim().parse().map_err(|_| bad())?;
        if count == 0 || count > MAX_SHARDS || index >= count {
            return Err(bad());
        }
        Ok(Self { index, count })
    }

    /// The directory name of its table, `shard-I-of-N`.
    #[must_use]
    pub fn dir_name(&self) -> String {
        format!("shard-{}-of-{}", self.index, self.count)
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// The shard of every cell of `plan` split `count` ways: longest processing time first (Graham
/// 1969) over units — whole frames when there are at least
/// [`FRAMES_PER_SHARD_TO_KEEP_FRAMES_WHOLE`] per shard, cells otherwise — in order of estimated
/// cost (greatest first, ties by number), each to the least-loaded shard (ties to the lowest
/// shard). A shard's load counts its frames' truths once each.
///
/// # Errors
/// [`SweepError::Shard`] if `count` is 0.
pub fn assign(plan: &Plan, count: usize) -> Result<Vec<usize>, SweepError> {
    if count == 0 {
        return Err(SweepError::Shard("a sweep needs at least one shard".into()));
    }
    let whole_frames = plan.frames.len() >= count * FRAMES_PER_SHARD_TO_KEEP_FRAMES_WHOLE;
    // Units: (the cells, their cost).
    let mut units: Vec<(Vec<usize>, f64)> = if whole_frames {
        let mut by_frame = vec![(Vec::new(), 0.0); plan.frames.len()];
        for cell in &plan.cells {
            let unit: &mut (Vec<usize>, f64) = &mut by_frame[cell.frame];
            unit.0.push(cell.index);
            unit.1 += cell.cost;
        }
        by_frame.retain(|u| !u.0.is_empty());
        by_frame
    } else {
        plan.cells.iter().map(|c| (vec![c.index], c.cost)).collect()
    };
    units.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0[0].cmp(&b.0[0])));
    // Loads are sums of non-negative costs, so their bit patterns order as they do.
    let mut heap: BinaryHeap<Reverse<(u64, usize)>> =
        (0..count).map(|s| Reverse((0f64.to_bits(), s))).collect();
    let mut frames: Vec<HashSet<usize>> = vec![HashSet::new(); count];
    let mut out = vec![0; plan.cells.len()];
    for (cells, cost) in units {
        let Reverse((load, shard)) = heap.pop().expect("at least one shard");
        let mut load = f64::from_bits(load) + cost;
        for cell in cells {
            out[cell] = shard;
            let frame = plan.cells[cell].frame;
            if frames[shard].insert(frame) {
                load += plan.frame_costs[frame];
            }
        }
        heap.push(Reverse((load.to_bits(), shard)));
    }
    Ok(out)
}

/// Each shard's estimated cost under `assignment` (cells plus the truth of each frame it touches).
#[must_use]
pub fn loads(plan: &Plan, assignment: &[usize], count: usize) -> Vec<f64> {
    let mut load = vec![0.0; count];
    let mut seen: Vec<HashSet<usize>> = vec![HashSet::new(); count];
    for cell in &plan.cells {
        let shard = assignment[cell.index];
        load[shard] += cell.cost;
        if seen[shard].insert(cell.frame) {
            load[shard] += plan.frame_costs[cell.frame];
        }
    }
    load
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_parse_and_refuse() {
        assert_eq!(Shard::parse("2/4"), Ok(Shard { index: 2, count: 4 }));
        for bad in ["4/4", "0/0", "1", "a/2", "-1/2", "1/100001"] {
            assert!(Shard::parse(bad).unwrap_err().contains("I/N"), "{bad}");
        }
    }
}
