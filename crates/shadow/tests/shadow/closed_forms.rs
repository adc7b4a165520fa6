//! The constructed matrices have the aliasing the closed forms predict (issue 5's proof): with the
//! map fitted to B = V, the perspective aliasing measured along the view axis (`measure`) equals
//! LiSPSM eq. 3 at γ = 90°, GMNPR's F (eq. 2) and CAD's m_z (eq. 12) at general angles, for every
//! parameter rule; the logarithmic map's is constant (ln(zf/zn) at 90°); PSM shifted by Δ equals
//! LiSPSM with n = zn + Δ (formulas.md §3.3).

use std::f64::consts::PI;

use glam::DVec3;
use proptest::prelude::*;
use shadowlab_params::{
    DepthRange, FrustumModel, HalfFov, LightAngle, ParameterRule, WarpParameter, cad, gmnpr,
    lispsm, logarithmic,
};
use shadowlab_shadow::{
    FocusPolicy, ShadowError, ShadowMapping, Technique, WarpChoice, measure, plan, psm,
};

use crate::support::{config, configuration, relative};

/// Agreement asked of measured and closed-form aliasing.
const AGREEMENT: f64 = 1e-6;
/// The closed forms assume the warp axis in the light–view plane; hull's light space blends it
/// toward the camera's diagonal below sin γ = 0.01, so the comparison starts just above.
const MIN_GAMMA_DEGREES: f64 = 0.6;

fn depths(near: f64, far: f64) -> impl Iterator<Item = f64> {
    (0..=6).map(move |k| near * (far / near).powf(f64::from(k) / 6.0))
}

proptest! {
    #![proptest_config(config(48))]

    /// Claim: for every parameter rule of `shadowlab-params` (and the uniform map), LiSPSM's matrix
    /// fitted to B = V has, at every depth of the view axis, the aliasing of the 2-D model — GMNPR's F
    /// and CAD's m_z (with res_c/res_l = 2, where m_z = F) — to 1e-6, over cameras at any position and
    /// orientation, fields of view 20°–120°, far/near 3 to 1e5, γ from 0.6° to 90°, the light above or
    /// below the view direction and in front of or behind the viewer.
    #[test]
    fn lispsm_matrices_have_the_model_aliasing(
        x in -50.0..50.0f64, y in -50.0..50.0f64, z in -50.0..50.0f64,
        yaw in -PI..PI, pitch in -1.2..1.2f64,
        fov in 20.0..120.0f64, near in 0.01..10.0f64, decades in 0.5..5.0f64,
        gamma_degrees in MIN_GAMMA_DEGREES..90.0f64, above in any::<bool>(), facing in any::<bool>(),
    ) {
        let far = near * 10f64.powf(decades);
        let input = configuration(DVec3::new(x, y, z), yaw, pitch, fov, near, far, gamma_degrees.to_radians(), above, facing, FocusPolicy::View);
        let model = FrustumModel::new(DepthRange::new(near, far).unwrap(), HalfFov::from_full_fov_degrees(fov).unwrap());
        let gamma = LightAngle::from_degrees(gamma_degrees).unwrap();
        let rules = ParameterRule::ALL.into_iter().map(|r| Technique::Lispsm(WarpChoice::Rule(r))).chain([Technique::Uniform]);
        for technique in rules {
            let setup = match plan(&input, technique) {
                Ok(setup) => setup,
                Err(ShadowError::NotDefined { .. }) => {
                    // Only GLPR may be undefined, and only where the model says so.
                    prop_assert_eq!(technique, Technique::Lispsm(WarpChoice::Rule(ParameterRule::Glpr)));
                    prop_assert!(ParameterRule::Glpr.warp(&model, gamma).is_none());
                    continue;
                }
                Err(e) => return Err(TestCaseError::fail(format!("{technique}: {e}"))),
            };
            prop_assert!(relative(setup.gamma, gamma.radians()) < 1e-9, "γ {} vs {}", setup.gamma, gamma.radians());
            let report = setup.warp.expect("a light-space warp");
            let warp = WarpParameter::from_lambda(report.lambda).unwrap();
            // B = V: the fitted depth is the model's warp depth d.
            prop_assert!(relative(report.depth, model.warp_depth(gamma)) < AGREEMENT, "d {} vs {}", report.depth, model.warp_depth(gamma));
            for t in depths(near, far) {
                let measured = measure::view_axis_error(&setup.mapping, &input.eye, t).expect("on the map");
                let f = gmnpr::error(&model, gamma, warp, t).unwrap();
                prop_assert!(relative(measured / model.half_fov().tan(), f) < AGREEMENT,
                    "{technique} at t = {t}: measured F {} vs GMNPR eq. 2 {f}", measured / model.half_fov().tan());
                if !warp.is_uniform() {
                    let m_z = cad::m_z(&model, gamma, report.lambda * model.warp_depth(gamma), t, 2.0).unwrap();
                    prop_assert!(relative(measured / model.half_fov().tan(), m_z) < AGREEMENT, "{technique}: CAD eq. 12 {m_z}");
                }
            }
        }
    }

    /// Claim: with the light perpendicular to the view, LiSPSM at the paper's n_opt has LiSPSM
    /// eq. 3's aliasing `(z − zn + n)²/z · (zf − zn)/(n (n + zf − zn))` at every depth.
    #[test]
    fn lispsm_at_ninety_degrees_is_equation_3(
        yaw in -PI..PI, pitch in -1.2..1.2f64, fov in 20.0..120.0f64,
        near in 0.01..10.0f64, decades in 0.5..5.0f64, above in any::<bool>(),
    ) {
        let far = near * 10f64.powf(decades);
        let input = configuration(DVec3::ZERO, yaw, pitch, fov, near, far, PI / 2.0, above, true, FocusPolicy::View);
        let setup = plan(&input, Technique::Lispsm(WarpChoice::PAPER)).unwrap();
        let range = DepthRange::new(near, far).unwrap();
        let n = setup.warp.unwrap().near_distance;
        prop_assert!(relative(n, lispsm::n_opt(range)) < AGREEMENT, "n {n} vs n_opt {}", lispsm::n_opt(range));
        for t in depths(near, far) {
            let measured = measure::view_axis_error(&setup.mapping, &input.eye, t).unwrap();
            let expected = lispsm::dp_ds(range, n, t).unwrap();
            prop_assert!(relative(measured, expected) < AGREEMENT, "t = {t}: {measured} vs eq. 3 {expected}");
        }
    }

    /// Claim: the logarithmic map's measured aliasing along the view axis is its closed form
    /// `ln(1 + 1/λ)·(1 + c/(t sin γ))`, c its reference point's offset from the eye, at every angle
    /// (γ from 0.6° to 90°, B = V); where the reference point is the eye (c = 0: the eye at least
    /// a tenth of z_n·d/(z_f − z_n) beyond B's near plane, γ > φ) that is the same at every depth: `ln(1 + 1/λ)`, and
    /// ln(zf/zn) at 90° (formulas.md §2.9).
    #[test]
    fn the_logarithmic_map_has_its_closed_form_aliasing(
        yaw in -PI..PI, pitch in -1.2..1.2f64, fov in 20.0..100.0f64,
        near in 0.01..10.0f64, decades in 0.5..5.0f64, above in any::<bool>(), facing in any::<bool>(),
        gamma_degrees in MIN_GAMMA_DEGREES..90.0f64, at_ninety in any::<bool>(),
    ) {
        let far = near * 10f64.powf(decades);
        let gamma_degrees = if at_ninety { 90.0 } else { gamma_degrees };
        let input = configuration(DVec3::ZERO, yaw, pitch, fov, near, far, gamma_degrees.to_radians(), above, facing, FocusPolicy::View);
        let setup = plan(&input, Technique::LOGARITHMIC).unwrap();
        let ShadowMapping::Logarithmic(map) = setup.mapping else { unreachable!("a logarithmic map") };
        let warp = setup.warp.as_ref().unwrap();
        let z_max = warp.inputs.iter().find(|(name, _)| *name == "z_max").unwrap().1;
        let at_eye = warp.lambda == -z_max / warp.depth;
        let constant = (1.0 / warp.lambda).ln_1p();
        if gamma_degrees == 90.0 {
            prop_assert!(at_eye);
            let range = DepthRange::new(near, far).unwrap();
            prop_assert!(relative(constant, logarithmic::dp_ds(range)) < AGREEMENT);
        }
        for t in depths(near, far) {
            let measured = measure::view_axis_error(&setup.mapping, &input.eye, t).unwrap();
            let closed = map.view_axis_error(setup.gamma.sin(), t);
            prop_assert!(relative(measured, closed) < AGREEMENT, "γ = {gamma_degrees}°, t = {t}: {measured} vs {closed}");
            if at_eye {
                prop_assert!(relative(measured, constant) < AGREEMENT, "t = {t}: {measured} vs {constant}");
            }
        }
    }

    /// Claim: PSM whose virtual camera is shifted back by Δ has, with the light perpendicular to the
    /// view, the aliasing of LiSPSM with n = zn + Δ (formulas.md §3.3): Δ → ∞ is uniform, Δ = 0 is
    /// PSM's `z/zn`-like warp.
    #[test]
    fn psm_shifted_by_delta_is_lispsm_with_n_zn_plus_delta(
        yaw in -PI..PI, pitch in -1.2..1.2f64, fov in 20.0..120.0f64,
        near in 0.01..10.0f64, decades in 0.5..5.0f64, above in any::<bool>(),
        shift_fraction in 0.0..50.0f64,
    ) {
        let far = near * 10f64.powf(decades);
        let input = configuration(DVec3::ZERO, yaw, pitch, fov, near, far, PI / 2.0, above, true, FocusPolicy::View);
        let shift = shift_fraction * near;
        let setup = psm::plan_with_shift(&input, Some(shift)).unwrap();
        let report = setup.psm.unwrap();
        prop_assert!(report.directional && !report.inverted);
        let range = DepthRange::new(near, far).unwrap();
        for t in depths(near, far) {
            let measured = measure::view_axis_error(&setup.mapping, &input.eye, t).unwrap();
            let expected = lispsm::dp_ds(range, near + shift, t).unwrap();
            prop_assert!(relative(measured, expected) < AGREEMENT, "Δ = {shift}, t = {t}: {measured} vs {expected}");
        }
    }
}
