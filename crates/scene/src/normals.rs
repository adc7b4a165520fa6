//! Vertex normals: area-weighted averages of the adjacent triangles' normals, and a normalisation
//! that neither overflows nor underflows.

use glam::DVec3;

/// The normal given to a vertex whose area-weighted normal has no direction: the vertex is in no
/// triangle, all its triangles have zero area, or their normals cancel (e.g. two coincident
/// triangles of opposite winding). It is `+z`.
pub const FALLBACK_NORMAL: DVec3 = DVec3::Z;

/// `v / |v|`, or `None` if `v` is zero or not finite. The vector is first divided by its largest
/// absolute component, so that `|v|` can neither overflow nor underflow.
pub(crate) fn unit(v: DVec3) -> Option<DVec3> {
    let largest = v.abs().max_element();
    if !(largest > 0.0 && largest.is_finite()) {
        return None;
    }
    let scaled = v / largest;
    Some(scaled / scaled.length())
}

/// The power of two that brings the largest absolute coordinate of `points` into `[1, 2)` (or 1 if
/// every coordinate is 0). Multiplying by a power of two is exact (barring underflow of coordinates
/// far smaller than the largest), so cross products of scaled edges cannot overflow.
fn normalising_scale(points: &[DVec3]) -> f64 {
    let largest = points
        .iter()
        .map(|p| p.abs().max_element())
        .fold(0.0_f64, f64::max);
    if largest == 0.0 {
        return 1.0;
    }
    // Clearing the mantissa leaves the power of two at or below `largest`; subnormal values have no
    // exponent bits, so they use the smallest normal power of two instead.
    let power = f64::from_bits(largest.to_bits() & 0x7ff0_0000_0000_0000).max(f64::MIN_POSITIVE);
    1.0 / power
}

/// Area-weighted vertex normals: for each vertex, the sum of the (unnormalised) cross products
/// `(b − a) × (c − a)` of its triangles, normalised; [`FALLBACK_NORMAL`] where the sum has no
/// direction. The cross product's length is twice the triangle's area, so large triangles count
/// more and degenerate ones not at all. Positions are scaled by a power of two first (see
/// [`normalising_scale`]), which changes no direction and makes the result independent of the
/// mesh's scale.
///
/// `triangles` must index into `positions` (checked by the caller).
pub(crate) fn area_weighted(positions: &[DVec3], triangles: &[[u32; 3]]) -> Vec<DVec3> {
    let scale = normalising_scale(positions);
    let mut sums = vec![DVec3::ZERO; positions.len()];
    for triangle in triangles {
        let [a, b, c] = triangle.map(|i| positions[i as usize] * scale);
        let cross = (b - a).cross(c - a);
        for &i in triangle {
            sums[i as usize] += cross;
        }
    }
    sums.into_iter()
        .map(|sum| unit(sum).unwrap_or(FALLBACK_NORMAL))
        .collect()
}
