//! The unit tests' random numbers: a xorshift64 generator, seeded by each test (so every run draws
//! the same numbers). Not for anything but tests.

/// Marsaglia's xorshift64 (shifts 13, 7, 17).
pub(crate) struct XorShift(u64);

impl XorShift {
    /// A generator started from `seed` (non-zero).
    pub(crate) fn new(seed: u64) -> Self {
        debug_assert_ne!(seed, 0);
        Self(seed)
    }

    /// The next 64 bits.
    pub(crate) fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    /// The next number in `0..n` (`n` > 0; modulo bias is of no concern here).
    pub(crate) fn below(&mut self, n: u64) -> u64 {
        self.next_u64() % n
    }

    /// The next number in `[0, 1)`, from the top 53 bits.
    #[expect(clippy::cast_precision_loss, reason = "53 bits, exact")]
    pub(crate) fn fraction(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
}
