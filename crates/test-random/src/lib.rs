//! The unit tests' deterministic numbers: SplitMix64 (Steele, Lea & Flood, "Fast Splittable
//! Pseudorandom Number Generators", OOPSLA 2014), seeded per test, so every run draws the same
//! numbers. A dev-dependency of the crates whose unit tests draw random inputs; not for anything
//! but tests.

use glam::DVec3;

/// SplitMix64 from the seed it holds.
pub struct SplitMix(pub u64);

impl SplitMix {
    /// The next 64 bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// A number in `[0, 1)` from the next 32 high bits.
    pub fn unit(&mut self) -> f64 {
        f64::from(u32::try_from(self.next_u64() >> 32).expect("32 bits")) / 4_294_967_296.0
    }

    /// A number in `[lo, hi)`.
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    /// A point of the cube `[−half, half)³`.
    pub fn vector(&mut self, half: f64) -> DVec3 {
        DVec3::new(
            self.range(-half, half),
            self.range(-half, half),
            self.range(-half, half),
        )
    }
}
