//! Perspective aliasing measured from a planned shadow map, to hold it against the closed forms.
//!
//! Along the view axis, the point at eye depth `t` is `e + t·v`. The shadow map sends it to window
//! coordinates `(x, y) ∈ [0, 1]²`; with `s` the distance travelled on the map,
//! `ds/dt = |d(x, y)/dt|`, the perspective aliasing in LiSPSM's normalisation (eq. 1 with
//! `cos α/cos β = 1`, the map spanning `[0, 1]`) is
//!
//! `dp/ds = (1/t)·dt/ds`.
//!
//! For the LiSPSM family fitted to B = V this is exactly the 2-D model's
//! `FrustumModel::view_axis_error` (CAD eq. 12, GMNPR eq. 2 up to their constant factors), and at
//! γ = 90° LiSPSM eq. 3 — the tests hold every technique to it.

use glam::DVec3;

use crate::input::Eye;
use crate::setup::ShadowMapping;

/// Relative step of the central differences used for non-projective maps; with Richardson
/// extrapolation the truncation error is of order `STEP⁴` and rounding `ε/STEP`, both far below
/// the 1e-6 the tests ask for.
const STEP: f64 = 1e-3;

/// `dp/ds` at eye depth `t` along the view axis of `eye`, measured from `mapping` (see the module
/// docs). `None` if the point is not mapped (behind a projection centre).
#[must_use]
pub fn view_axis_error(mapping: &ShadowMapping, eye: &Eye, t: f64) -> Option<f64> {
    let (e, v) = (eye.pose.eye(), eye.pose.forward());
    let speed = match mapping {
        ShadowMapping::Projective(_) => {
            // Each window coordinate is (a + b t)/(c + d t) of the clip rows: exact derivative.
            let m = mapping.clip_from_world()?;
            let (p, dp) = (m * (e + v * t).extend(1.0), m * v.extend(0.0));
            if p.w <= 0.0 {
                return None;
            }
            let derivative = |k: usize| 0.5 * (dp[k] * p.w - p[k] * dp.w) / (p.w * p.w);
            DVec3::new(derivative(0), derivative(1), 0.0).length()
        }
        ShadowMapping::Logarithmic(_) | ShadowMapping::Paraboloid(_) => {
            let at = |t: f64| mapping.window(e + v * t).map(|w| w.truncate());
            let central = |h: f64| Some((at(t + h)? - at(t - h)?) / (2.0 * h));
            let h = STEP * t;
            // Richardson: (4·D(h/2) − D(h))/3 cancels the h² term.
            let d = (central(0.5 * h)? * 4.0 - central(h)?) / 3.0;
            d.length()
        }
    };
    Some(1.0 / (t * speed))
}
