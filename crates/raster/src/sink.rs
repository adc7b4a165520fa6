//! Sinks: what a tile's fragments are written into — depth keys through the depth test, the two
//! nearest keys, or keys and triangle ids — eight pixels of a block row at a time, with selects
//! rather than branches.

use std::marker::PhantomData;

use crate::depth::{DepthCompare, DepthKey};
use crate::kernel::{BLOCK, HALF, Lanes, Sink};

/// A depth comparison as a type, so the common `Less` compiles without a per-fragment branch. A
/// draw chooses its comparison once (`pipeline`), and every sink of the draw is compiled for it.
pub(crate) trait Compare: Copy + Send + Sync {
    /// Whether a fragment with key `new` replaces the stored `old`.
    fn passes(&self, new: u32, old: u32) -> bool;

    /// The stored value after a fragment with key `new`, uncovered where `uncovered` is all ones,
    /// meets `old`; and all ones if the fragment passed (zero otherwise).
    #[inline(always)]
    fn merge(&self, uncovered: u32, new: u32, old: u32) -> (u32, u32) {
        let pass = !uncovered & mask(self.passes(new, old));
        (select(pass, new, old), pass)
    }
}

/// `new < old`.
#[derive(Clone, Copy)]
pub(crate) struct Less;

impl Compare for Less {
    #[inline(always)]
    fn passes(&self, new: u32, old: u32) -> bool {
        new < old
    }

    /// `min(new | uncovered, old)`: an uncovered lane offers the largest key, which never wins; a
    /// fragment passed exactly where the value changed.
    #[inline(always)]
    fn merge(&self, uncovered: u32, new: u32, old: u32) -> (u32, u32) {
        let merged = (new | uncovered).min(old);
        (merged, mask(merged != old))
    }
}

impl Compare for DepthCompare {
    #[inline(always)]
    fn passes(&self, new: u32, old: u32) -> bool {
        DepthCompare::passes(*self, new, old)
    }
}

/// Writes depth keys through the depth test.
pub(crate) struct DepthSink<'a, K, C> {
    keys: &'a mut [u32],
    compare: C,
    key: PhantomData<K>,
}

impl<'a, K, C> DepthSink<'a, K, C> {
    /// A sink into one tile's keys.
    pub(crate) fn new(keys: &'a mut [u32], compare: C) -> Self {
        Self {
            keys,
            compare,
            key: PhantomData,
        }
    }
}

/// The eight stored values of a block row whose second half lies `SPLIT` after its first (see
/// [`Sink::row`]): one load when the halves are adjacent, two otherwise.
#[inline(always)]
fn load<const SPLIT: usize>(values: &[u32], start: usize) -> Lanes<u32> {
    let mut lanes = [0; BLOCK];
    if SPLIT == HALF {
        lanes.copy_from_slice(&values[start..start + BLOCK]);
    } else {
        lanes[..HALF].copy_from_slice(&values[start..start + HALF]);
        lanes[HALF..].copy_from_slice(&values[start + SPLIT..start + SPLIT + HALF]);
    }
    lanes
}

/// Stores what [`load`] loaded.
#[inline(always)]
fn store<const SPLIT: usize>(values: &mut [u32], start: usize, lanes: &Lanes<u32>) {
    if SPLIT == HALF {
        values[start..start + BLOCK].copy_from_slice(lanes);
    } else {
        values[start..start + HALF].copy_from_slice(&lanes[..HALF]);
        values[start + SPLIT..start + SPLIT + HALF].copy_from_slice(&lanes[HALF..]);
    }
}

/// All ones where `pass`, zero otherwise (written as a select of constants, which compiles to a
/// vector compare; going through `u32::from(bool)` makes LLVM shuffle single bits).
#[inline(always)]
fn mask(pass: bool) -> u32 {
    if pass { u32::MAX } else { 0 }
}

/// `new` where `pass` (all ones), `old` elsewhere: a select, not a branch — whether a fragment
/// passes is as good as random, and a mispredicted branch costs more than the whole test.
#[inline(always)]
fn select(pass: u32, new: u32, old: u32) -> u32 {
    (new & pass) | (old & !pass)
}

impl<K: DepthKey, C: Compare> Sink for DepthSink<'_, K, C> {
    #[inline(always)]
    fn row<const SPLIT: usize>(
        &mut self,
        start: usize,
        uncovered: &Lanes<u32>,
        z: &Lanes<f64>,
        _triangle: u32,
    ) -> u64 {
        let mut keys = load::<SPLIT>(self.keys, start);
        let mut passed = 0;
        for k in 0..BLOCK {
            let key = K::encode(z[k]);
            let (merged, pass) = self.compare.merge(uncovered[k], key, keys[k]);
            keys[k] = merged;
            passed += pass & 1;
        }
        store::<SPLIT>(self.keys, start, &keys);
        u64::from(passed)
    }

    #[inline(always)]
    fn fragment(&mut self, index: usize, z: f64, _triangle: u32) -> u64 {
        let key = K::encode(z);
        let old = &mut self.keys[index];
        let (merged, pass) = self.compare.merge(0, key, *old);
        *old = merged;
        u64::from(pass & 1)
    }
}

/// Keeps the two nearest keys.
pub(crate) struct PairSink<'a, K> {
    nearest: &'a mut [u32],
    second: &'a mut [u32],
    key: PhantomData<K>,
}

impl<'a, K> PairSink<'a, K> {
    /// A sink into one tile's nearest and second-nearest keys.
    pub(crate) fn new(nearest: &'a mut [u32], second: &'a mut [u32]) -> Self {
        Self {
            nearest,
            second,
            key: PhantomData,
        }
    }
}

impl<K: DepthKey> Sink for PairSink<'_, K> {
    #[inline(always)]
    fn row<const SPLIT: usize>(
        &mut self,
        start: usize,
        uncovered: &Lanes<u32>,
        z: &Lanes<f64>,
        _triangle: u32,
    ) -> u64 {
        let mut nearest = load::<SPLIT>(self.nearest, start);
        let mut second = load::<SPLIT>(self.second, start);
        let mut passed = 0;
        for k in 0..BLOCK {
            let key = K::encode(z[k]);
            let (near, next) = (nearest[k], second[k]);
            let nearer = !uncovered[k] & mask(key < near);
            let between = !uncovered[k] & !nearer & mask(key < next);
            nearest[k] = select(nearer, key, near);
            second[k] = select(nearer, near, select(between, key, next));
            passed += u64::from((nearer | between) & 1);
        }
        store::<SPLIT>(self.nearest, start, &nearest);
        store::<SPLIT>(self.second, start, &second);
        passed
    }

    #[inline(always)]
    fn fragment(&mut self, index: usize, z: f64, _triangle: u32) -> u64 {
        let key = K::encode(z);
        let (near, next) = (self.nearest[index], self.second[index]);
        if key < near {
            self.second[index] = near;
            self.nearest[index] = key;
            1
        } else if key < next {
            self.second[index] = key;
            1
        } else {
            0
        }
    }
}

/// Writes depth keys and triangle ids through the depth test.
pub(crate) struct EyeSink<'a, K, C> {
    keys: &'a mut [u32],
    triangles: &'a mut [u32],
    compare: C,
    key: PhantomData<K>,
}

impl<'a, K, C> EyeSink<'a, K, C> {
    /// A sink into one tile's keys and triangle ids.
    pub(crate) fn new(keys: &'a mut [u32], triangles: &'a mut [u32], compare: C) -> Self {
        Self {
            keys,
            triangles,
            compare,
            key: PhantomData,
        }
    }
}

impl<K: DepthKey, C: Compare> Sink for EyeSink<'_, K, C> {
    #[inline(always)]
    fn row<const SPLIT: usize>(
        &mut self,
        start: usize,
        uncovered: &Lanes<u32>,
        z: &Lanes<f64>,
        triangle: u32,
    ) -> u64 {
        let mut keys = load::<SPLIT>(self.keys, start);
        let mut ids = load::<SPLIT>(self.triangles, start);
        let mut passed = 0;
        for k in 0..BLOCK {
            let key = K::encode(z[k]);
            let (merged, pass) = self.compare.merge(uncovered[k], key, keys[k]);
            keys[k] = merged;
            ids[k] = select(pass, triangle, ids[k]);
            passed += u64::from(pass & 1);
        }
        store::<SPLIT>(self.keys, start, &keys);
        store::<SPLIT>(self.triangles, start, &ids);
        passed
    }

    #[inline(always)]
    fn fragment(&mut self, index: usize, z: f64, triangle: u32) -> u64 {
        let key = K::encode(z);
        let (merged, pass) = self.compare.merge(0, key, self.keys[index]);
        self.keys[index] = merged;
        self.triangles[index] = select(pass, triangle, self.triangles[index]);
        u64::from(pass & 1)
    }
}
