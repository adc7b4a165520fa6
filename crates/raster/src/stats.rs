//! What a draw did with its triangles, counted.

/// What happened to the triangles of a draw. Every triangle is counted exactly once among
/// `drawn`, `degenerate`, `culled`, `empty`, `outside` and `clipped`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DrawStats {
    /// Triangles submitted.
    pub triangles: u64,
    /// Rasterized without clipping.
    pub drawn: u64,
    /// Zero area after snapping (never drawn).
    pub degenerate: u64,
    /// Discarded by the cull mode.
    pub culled: u64,
    /// Inside the clip volume but covering no pixel centre's bounding box.
    pub empty: u64,
    /// Entirely outside one plane of the clip volume.
    pub outside: u64,
    /// Crossing the near or far plane or the guard band, and clipped.
    pub clipped: u64,
    /// Pieces the clipped triangles were cut into that were rasterized.
    pub clipped_pieces: u64,
    /// Fragments that passed the depth test (or, for [`crate::Rasterizer::for_each_fragment`], all covered
    /// pixels).
    pub fragments: u64,
}

impl DrawStats {
    /// Adds `other`'s counts to these.
    pub(crate) fn add(&mut self, other: &Self) {
        self.triangles += other.triangles;
        self.drawn += other.drawn;
        self.degenerate += other.degenerate;
        self.culled += other.culled;
        self.empty += other.empty;
        self.outside += other.outside;
        self.clipped += other.clipped;
        self.clipped_pieces += other.clipped_pieces;
        self.fragments += other.fragments;
    }
}
