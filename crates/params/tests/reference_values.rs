//! Every reference value of formulas.md §8 (12 significant digits, computed independently with sympy
//! and mpmath by the author of that file), pinned to [`REFERENCE_TOLERANCE`] relative.
//! Values quoted elsewhere in formulas.md with fewer digits are pinned to the digits printed.

use shadowlab_params::cad::{self, Falloff};
use shadowlab_params::splits::SplitScheme;
use shadowlab_params::{
    DepthRange, FrustumModel, HalfFov, LightAngle, WarpParameter, gmnpr, lispsm, logarithmic,
};

/// The agreement the issue asks for with the 12-digit values of formulas.md §8.
const REFERENCE_TOLERANCE: f64 = 1e-10;

#[track_caller]
fn assert_close(actual: f64, expected: f64, tolerance: f64, what: &str) {
    let scale = expected.abs().max(f64::MIN_POSITIVE);
    let error = (actual - expected).abs() / scale;
    assert!(
        error <= tolerance,
        "{what}: got {actual:.15e}, expected {expected:.15e} (relative error {error:.2e} > {tolerance:.0e})"
    );
}

#[track_caller]
fn assert_ref(actual: f64, expected: f64, what: &str) {
    assert_close(actual, expected, REFERENCE_TOLERANCE, what);
}

fn range(near: f64, far: f64) -> DepthRange {
    DepthRange::new(near, far).unwrap()
}

/// The model of all tables: φ = 30° (a 60° field of view).
fn model(near: f64, far: f64) -> FrustumModel {
    FrustumModel::new(
        range(near, far),
        HalfFov::from_full_fov_degrees(60.0).unwrap(),
    )
}

fn deg(gamma: f64) -> LightAngle {
    LightAngle::from_degrees(gamma).unwrap()
}

#[test]
fn section_8_1_lispsm_perpendicular() {
    // zf, n_opt, max error at n_opt, its minimum, ln(zf/zn), normalised dp/dt at zn.
    let table = [
        (100.0, 11.0, 9.9, 3.27272727273, 4.60517018599, 10.0),
        (400.0, 21.0, 19.95, 3.61904761905, 5.99146454711, 20.0),
        (
            800.0,
            29.2842712475,
            28.2489159084,
            3.72681580728,
            6.68461172767,
            28.2842712475,
        ),
        (1e6, 1001.0, 999.999, 3.99200799201, 13.815510558, 1000.0),
    ];
    for (zf, n_opt, max, min, log, dp_dt) in table {
        let r = range(1.0, zf);
        let what = |s: &str| format!("zf = {zf}: {s}");
        assert_ref(
            lispsm::uniform_dp_ds(r, 1.0).unwrap(),
            zf - 1.0,
            &what("uniform max"),
        );
        assert_ref(
            lispsm::psm_dp_ds(r, zf).unwrap(),
            zf - 1.0,
            &what("PSM max"),
        );
        let uniform_at_far = lispsm::uniform_dp_ds(r, zf).unwrap();
        assert_ref(uniform_at_far, (zf - 1.0) / zf, &what("uniform at zf"));
        assert_ref(
            lispsm::psm_dp_ds(r, 1.0).unwrap(),
            (zf - 1.0) / zf,
            &what("PSM at zn"),
        );
        assert_ref(lispsm::n_opt(r), n_opt, &what("n_opt"));
        assert_ref(
            lispsm::max_error_at_n_opt(r),
            max,
            &what("max error, closed form"),
        );
        assert_ref(
            lispsm::max_error(r, n_opt).unwrap(),
            max,
            &what("max error, eq. 3"),
        );
        assert_ref(
            lispsm::min_error_at_n_opt(r),
            min,
            &what("min error, closed form"),
        );
        let at_minimum = lispsm::dp_ds(r, lispsm::n_opt(r), zf.sqrt()).unwrap();
        assert_ref(at_minimum, min, &what("eq. 3 at sqrt(zn zf)"));
        assert_ref(logarithmic::dp_ds(r), log, &what("log ideal"));
        assert_ref(
            lispsm::dp_dt(r, lispsm::n_opt(r), 1.0).unwrap(),
            dp_dt,
            &what("dp/dt at zn"),
        );
        // Uniform and PSM cross at sqrt(zn zf), where both equal LiSPSM's maximum.
        let z = zf.sqrt();
        assert_ref(
            lispsm::uniform_dp_ds(r, z).unwrap(),
            max,
            &what("uniform at crossover"),
        );
        assert_ref(
            lispsm::psm_dp_ds(r, z).unwrap(),
            max,
            &what("PSM at crossover"),
        );
    }
}

#[test]
fn section_8_2_lispsm_general_angle() {
    // γ, n'_opt = n_opt/sin γ, d, Δz n', λ paper, λ Δz (zn = 1, zf = 100, φ = 30°, B = V).
    let table = [
        (90.0, 11.0, 99.0, 11.0, 0.111111111111, 0.111111111111),
        (
            60.0,
            12.7017059222,
            114.892703569,
            12.7305374412,
            0.110552763819,
            0.110803706813,
        ),
        (
            45.0,
            15.5563491861,
            111.236648674,
            14.0361142587,
            0.139849135797,
            0.126182462579,
        ),
        (
            35.0,
            19.1779147518,
            104.55077018,
            15.3566136564,
            0.183431597097,
            0.146881879779,
        ),
        (30.0, 22.0, 100.0, 16.2828568571, 0.22, 0.162828568571),
        (
            20.0,
            32.1618484018,
            108.506357513,
            20.9737350846,
            0.296405198173,
            0.193294988103,
        ),
        (
            10.0,
            63.3464753146,
            113.71580426,
            31.9890326724,
            0.557059554972,
            0.281306832243,
        ),
        (
            5.0,
            126.210845702,
            115.030655422,
            49.5719395878,
            1.09719313725,
            0.430945467589,
        ),
        (
            1.0,
            630.285573484,
            115.452467189,
            156.789465245,
            5.45926465521,
            1.35804343607,
        ),
    ];
    let m = model(1.0, 100.0);
    for (g, n_paper, d, n_dz, lambda_paper, lambda_dz) in table {
        let gamma = deg(g);
        let what = |s: &str| format!("γ = {g}°: {s}");
        assert_ref(
            lispsm::n_opt_general(m.range(), gamma),
            n_paper,
            &what("n_opt/sin γ"),
        );
        assert_ref(m.warp_depth(gamma), d, &what("model depth d"));
        assert_ref(
            lispsm::n_delta_z(1.0, d, gamma).unwrap(),
            n_dz,
            &what("Δz variant"),
        );
        let lambda = gmnpr::lambda_lispsm(&m, gamma).lambda();
        assert_ref(lambda, lambda_paper, &what("λ of n_opt/sin γ"));
        let rule = shadowlab_params::ParameterRule::LispsmDeltaZ
            .warp(&m, gamma)
            .unwrap();
        assert_ref(rule.lambda(), lambda_dz, &what("λ of the Δz variant"));
    }
    let m = model(1.0, 800.0);
    let gamma = deg(45.0);
    assert_ref(
        lispsm::n_opt_general(m.range(), gamma),
        41.4142135624,
        "zf = 800: n_opt/sin γ",
    );
    let d = m.warp_depth(gamma);
    assert_ref(
        lispsm::n_delta_z(1.0, d, gamma).unwrap(),
        36.9593618336,
        "zf = 800: Δz",
    );
}

/// γ, raw n'_1, raw n'_2 (NaN: not tabulated), n' with r = eq. 18, eq. 17, sin², λ for eq. 18
/// (NaN: not tabulated), and the minimax n' of the model.
type CadRow = (f64, f64, f64, f64, f64, f64, f64, f64);

fn check_cad_table(m: &FrustumModel, rows: &[CadRow]) {
    for &(g, n1, n2, eq18, eq17, sin2, lambda18, minimax) in rows {
        let gamma = deg(g);
        let what = |s: &str| format!("f = {}, γ = {g}°: {s}", m.range().far());
        assert_ref(cad::n1(m, gamma), n1, &what("raw n'_1"));
        if !n2.is_nan() {
            assert_ref(cad::n2(m, gamma), n2, &what("raw n'_2"));
        }
        assert_ref(
            cad::n_prime(m, gamma, Falloff::Eq18),
            eq18,
            &what("n' eq. 18"),
        );
        assert_ref(
            cad::n_prime(m, gamma, Falloff::Eq17),
            eq17,
            &what("n' eq. 17"),
        );
        assert_ref(
            cad::n_prime(m, gamma, Falloff::SinSquared),
            sin2,
            &what("n' sin²"),
        );
        if !lambda18.is_nan() {
            let lambda = cad::warp(m, gamma, Falloff::Eq18).lambda();
            assert_ref(lambda, lambda18, &what("λ eq. 18"));
        }
        let n_minimax = gmnpr::lambda_minimax(m, gamma).near_distance(m.warp_depth(gamma));
        assert_ref(n_minimax, minimax, &what("minimax n'"));
    }
}

#[test]
fn section_8_3_cad_generalized_parameter_f_100() {
    let m = model(1.0, 100.0);
    assert_ref(m.far_half_height(), 57.735026919, "b");
    assert_ref(m.near_half_height(), 0.57735026919, "a");
    let limit = cad::gamma_lim(&m);
    assert_ref(limit.degrees(), 30.4986768609, "γ_lim in degrees");
    assert_ref(limit.radians(), 0.532302328724, "γ_lim in radians");
    assert_ref(cad::n1(&m, limit), 5.08523452167, "n'_1(γ_lim)");
    assert_ref(cad::gamma0(&m).degrees(), 27.6933585688, "γ_0");
    let nan = f64::NAN;
    #[rustfmt::skip]
    let rows: [CadRow; 9] = [
        (90.0, 11.0, nan, 11.0, 11.0, 11.0, 0.111111111111, 11.0),
        (60.0, 9.23760430703, nan, 9.23760430703, 9.23760430703, 9.23760430703, 0.0804020100503, 9.23760430703),
        (45.0, 7.36992630259, nan, 7.36992630259, 7.36992630259, 7.36992630259, 0.0662544798897, 7.36992630259),
        (35.0, 5.83640314658, nan, 5.83640314658, 5.83640314658, 5.83640314658, 0.055823626517, 5.83640314658),
        (30.0, 5.0, nan, 5.21927010852, 5.08691223041, 5.08859049265, 0.0521927010852, 5.0),
        (20.0, 3.21968978902, -16.6309629908, 10.4797147524, 5.9314257713, 6.91842461355, 0.0965815735829, 32.6755840999),
        (10.0, 1.34155093303, -37.7566025868, 39.1998809984, 10.3239340599, 20.9594295048, 0.344717968214, 131.193353946),
        (5.0, 0.383559893116, -47.9281960086, 154.214282407, 19.9670021835, 78.3997619969, 1.34063638811, 325.870446798),
        (1.0, -0.385285865137, -55.8064688866, 3834.94579252, 98.7788872084, 1918.74504835, 33.2166638434, 1870.93491429),
    ];
    check_cad_table(&m, &rows);
}

#[test]
fn section_8_3_cad_generalized_parameter_f_800() {
    let m = model(1.0, 800.0);
    assert_ref(m.far_half_height(), 461.880215352, "b");
    let limit = cad::gamma_lim(&m);
    assert_ref(limit.degrees(), 30.062063266, "γ_lim in degrees");
    assert_ref(limit.radians(), 0.524681983935, "γ_lim in radians");
    assert_ref(cad::n1(&m, limit), 14.1699111799, "n'_1(γ_lim)");
    assert_ref(cad::gamma0(&m).degrees(), 29.1455628107, "γ_0");
    let nan = f64::NAN;
    #[rustfmt::skip]
    let rows: [CadRow; 9] = [
        (90.0, 29.2842712475, nan, 29.2842712475, 29.2842712475, 29.2842712475, nan, 29.2842712475),
        (60.0, 25.072247697, nan, 25.072247697, 25.072247697, 25.072247697, nan, 25.072247697),
        (45.0, 20.2988584907, nan, 20.2988584907, 20.2988584907, 20.2988584907, nan, 20.2988584907),
        (35.0, 16.32383029, nan, 16.32383029, 16.32383029, 16.32383029, nan, 16.32383029),
        (30.0, 14.1421356237, nan, 14.2160124353, 14.1699856892, 14.1700601989, nan, 14.1421356237),
        (20.0, 9.47327886168, nan, 28.4462756367, 16.3824909471, 18.9405569466, nan, 255.312043612),
        (10.0, 4.51658131512, nan, 106.193666799, 28.3929991079, 56.8925512735, nan, 1036.36676857),
        (5.0, 1.97713913429, nan, 417.567424786, 54.8589979202, 212.387333598, nan, 2580.09298193),
        (1.0, -0.0661813319168, nan, 10382.3042535, 271.308671868, 5194.69702362, nan, 14832.3040649),
    ];
    check_cad_table(&m, &rows);
}

/// θ, λ_GMNPR, λ_LiSPSM, λ_minimax, F_max GMNPR, F_max LiSPSM, F_LiSPSM(n)/F_LiSPSM(f) (NaN: not
/// tabulated).
type GmnprRow = (f64, f64, f64, f64, f64, f64, f64);

fn check_gmnpr_table(m: &FrustumModel, rows: &[GmnprRow]) {
    for &(t, l_gmnpr, l_lispsm, l_minimax, f_gmnpr, f_lispsm, ratio) in rows {
        let theta = deg(t);
        let what = |s: &str| format!("f = {}, θ = {t}°: {s}", m.range().far());
        let gm = gmnpr::lambda_gmnpr(m, theta);
        let li = gmnpr::lambda_lispsm(m, theta);
        assert_ref(gm.lambda(), l_gmnpr, &what("λ_GMNPR"));
        assert_ref(li.lambda(), l_lispsm, &what("λ_LiSPSM"));
        assert_ref(
            gmnpr::lambda_minimax(m, theta).lambda(),
            l_minimax,
            &what("λ_minimax"),
        );
        assert_ref(
            gmnpr::max_error(m, theta, gm),
            f_gmnpr,
            &what("F_max GMNPR"),
        );
        assert_ref(
            gmnpr::max_error(m, theta, li),
            f_lispsm,
            &what("F_max LiSPSM"),
        );
        if !ratio.is_nan() {
            let (n, f) = (m.range().near(), m.range().far());
            let at_near = gmnpr::error(m, theta, li, n).unwrap();
            let at_far = gmnpr::error(m, theta, li, f).unwrap();
            assert_ref(at_near / at_far, ratio, &what("F_LiSPSM(n)/F_LiSPSM(f)"));
        }
    }
}

#[test]
fn section_8_4_gmnpr_f_100() {
    #[rustfmt::skip]
    let rows: [GmnprRow; 9] = [
        (90.0, 0.111111111111, 0.111111111111, 0.111111111111, 17.1473029949, 17.1473029949, 1.0),
        (60.0, 0.0804020100503, 0.110552763819, 0.0804020100503, 18.1857782248, 23.9261337646, 1.73130193906),
        (45.0, 0.0662544798897, 0.139849135797, 0.0662544798897, 18.8584930442, 35.2076074809, 3.44858229158),
        (35.0, 0.055823626517, 0.183431597097, 0.055823626517, 19.5074561778, 51.3792273647, 6.60966062755),
        (30.0, 0.05, 0.22, 0.05, 19.959823592, 65.3390999502, 9.765625),
        (20.0, 0.0866025403784, 0.296405198173, 0.301139811977, 440.145885628, 335.471634121, 36.9870831977),
        (10.0, 0.186602540378, 0.557059554972, 1.15369499253, 1468.54480692, 1073.12062292, 73.442128617),
        (5.0, 0.379787705636, 1.09719313725, 2.83290089588, 2825.38219839, 2301.92234899, 90.8278628565),
        (1.0, 1.90942296485, 5.45926465521, 16.2052397825, 11825.3451491, 11481.3414953, 99.4983752482),
    ];
    check_gmnpr_table(&model(1.0, 100.0), &rows);
}

#[test]
fn section_8_4_gmnpr_f_800() {
    let nan = f64::NAN;
    #[rustfmt::skip]
    let rows: [GmnprRow; 9] = [
        (90.0, 0.0366511530006, 0.0366511530006, 0.0366511530006, 48.9285576121, 48.9285576121, nan),
        (60.0, 0.0271584783435, 0.0366282317041, 0.0271584783435, 49.9492965013, 66.3581743466, nan),
        (45.0, 0.0227569454262, 0.0464292609527, 0.0227569454262, 50.590668466, 98.8633946625, nan),
        (35.0, 0.0195002066012, 0.0609902286038, 0.0195002066012, 51.1930943758, 148.01643256, nan),
        (30.0, 0.0176776695297, 0.0732106781187, 0.0176776695297, 51.602914446, 192.28868572, nan),
        (20.0, 0.0306186217848, 0.0986364798008, 0.294121065189, 6487.75062871, 3267.8173045, nan),
        (10.0, 0.0659739608441, 0.185375944418, 1.13920705142, 22057.2603699, 11725.2780092, nan),
        (5.0, 0.134275231033, 0.36511933457, 2.80370151382, 37467.9255132, 22866.9536365, nan),
        (1.0, 0.6750829633, 1.81671121562, 16.0588859922, 109071.18652, 94893.2053893, nan),
    ];
    check_gmnpr_table(&model(1.0, 800.0), &rows);
}

#[test]
fn section_8_4_special_angles() {
    for (far, theta0, theta1, lambda_at_theta1) in [
        (100.0, 27.6933585688, 28.9537861393, 0.0270462766947),
        (800.0, 29.1455628107, 29.5862605182, 0.00908033575276),
    ] {
        let m = model(1.0, far);
        let what = |s: &str| format!("f = {far}: {s}");
        assert_ref(gmnpr::theta0(&m).degrees(), theta0, &what("θ_0"));
        let t1 = gmnpr::theta1(&m);
        assert_ref(t1.degrees(), theta1, &what("θ1"));
        assert_ref(gmnpr::lambda2(&m, t1), lambda_at_theta1, &what("λ2 at θ1"));
        assert_ref(
            gmnpr::lambda_near_minimizer(&m, t1),
            lambda_at_theta1,
            &what("μ/(1−2μ) at θ1"),
        );
        assert_ref(
            gmnpr::lambda2(&m, gmnpr::theta0(&m)) + 1.0,
            1.0,
            &what("λ2(θ_0) = 0"),
        );
    }
    let m = model(1.0, 100.0);
    for (t, raw) in [
        (20.0, -0.153271783995),
        (10.0, -0.332025990867),
        (5.0, -0.416655854328),
        (1.0, -0.483371817382),
    ] {
        assert_ref(gmnpr::lambda2(&m, deg(t)), raw, &format!("raw λ2 at {t}°"));
    }
}

/// formulas.md §5.4 and §5.7, printed with 3–5 significant digits.
#[test]
fn sections_5_4_and_5_7_values_to_their_printed_digits() {
    let m = model(1.0, 100.0);
    assert_ref(gmnpr::lambda1(&m, deg(30.0)), 0.05, "λ1(φ), f/n = 100");
    assert_ref(
        gmnpr::lambda1(&model(1.0, 800.0), deg(30.0)),
        0.0176776695297,
        "λ1(φ), f/n = 800",
    );
    // Slopes at φ by central differences (step 1e-6 rad), to the printed 3 digits.
    let phi = 30f64.to_radians();
    let h = 1e-6;
    let slope = |f: &dyn Fn(LightAngle) -> f64| {
        let at = |x: f64| f(LightAngle::from_radians(x).unwrap());
        (at(phi + h) - at(phi - h)) / (2.0 * h)
    };
    assert_close(
        slope(&|g| gmnpr::lambda1(&m, g)),
        0.0699,
        2e-3,
        "dλ1/dθ at φ",
    );
    assert_close(
        slope(&|g| gmnpr::lambda2(&m, g)),
        1.270,
        1e-3,
        "dλ2/dθ at φ",
    );
    let star = |g| gmnpr::lambda2_star(&m, g).map_or(f64::NAN, WarpParameter::lambda);
    let below = (star(LightAngle::from_radians(phi).unwrap())
        - star(LightAngle::from_radians(phi - h).unwrap()))
        / h;
    assert_close(below, -0.150, 4e-3, "dλ2*/dθ at φ");
    // λ_LiSPSM's near/far error ratio (§5.7).
    for (far, t, ratio) in [
        (100.0, 80.0, 1.0736),
        (100.0, 60.0, 1.7313),
        (100.0, 45.0, 3.4486),
        (100.0, 35.0, 6.6097),
        (100.0, 31.0, 9.0001),
        (100.0, 30.0, 9.7656),
        (800.0, 30.0, 13.274),
    ] {
        let m = model(1.0, far);
        let w = gmnpr::lambda_lispsm(&m, deg(t));
        let r =
            gmnpr::error(&m, deg(t), w, 1.0).unwrap() / gmnpr::error(&m, deg(t), w, far).unwrap();
        assert_close(
            r,
            ratio,
            1e-4,
            &format!("F_L(n)/F_L(f), f = {far}, θ = {t}°"),
        );
    }
}

#[test]
fn section_8_5_logarithmic_partitions() {
    // f, k, interior boundaries, per-partition max error: uniform, LiSPSM, logarithmic.
    type Row = (f64, usize, &'static [f64], f64, f64, f64);
    let table: [Row; 6] = [
        // The table's 2.30258509299 is ln 10.
        (
            100.0,
            2,
            &[10.0],
            9.0,
            2.84604989415,
            std::f64::consts::LN_10,
        ),
        (
            100.0,
            3,
            &[4.64158883361, 21.5443469003],
            3.64158883361,
            1.69027580667,
            1.53505672866,
        ),
        (
            100.0,
            4,
            &[3.16227766017, 10.0, 31.6227766017],
            2.16227766017,
            1.21593808485,
            1.1512925465,
        ),
        (
            800.0,
            2,
            &[28.2842712475],
            27.2842712475,
            5.13026574229,
            3.34230586383,
        ),
        (
            800.0,
            3,
            &[9.28317766723, 86.1773876013],
            8.28317766723,
            2.71862086392,
            2.22820390922,
        ),
        (
            800.0,
            4,
            &[5.31829589694, 28.2842712475, 150.424123723],
            4.31829589694,
            1.87251863852,
            1.67115293192,
        ),
    ];
    for (far, k, interior, uniform, lispsm_max, log) in table {
        let b = SplitScheme::Logarithmic
            .boundaries(range(1.0, far), k)
            .unwrap();
        let what = |s: &str| format!("f = {far}, k = {k}: {s}");
        assert_eq!((b[0], b[k]), (1.0, far), "{}", what("exact endpoints"));
        for (x, y) in b[1..k].iter().zip(interior) {
            assert_ref(*x, *y, &what("boundary"));
        }
        assert_ref(b[1] / b[0], uniform + 1.0, &what("ratio"));
        for w in b.windows(2) {
            let part = range(w[0], w[1]);
            assert_ref(
                lispsm::uniform_dp_ds(part, w[0]).unwrap(),
                uniform,
                &what("uniform"),
            );
            assert_ref(
                lispsm::max_error_at_n_opt(part),
                lispsm_max,
                &what("LiSPSM"),
            );
            assert_ref(logarithmic::dp_ds(part), log, &what("log"));
        }
    }
}

#[test]
fn section_8_6_adaptive_partitions() {
    type Row = (f64, f64, &'static [&'static [f64]]);
    let table: [Row; 10] = [
        (
            100.0,
            90.0,
            &[
                &[10.0],
                &[4.64158883361, 21.5443469003],
                &[3.16227766017, 10.0, 31.6227766017],
            ],
        ),
        (
            100.0,
            60.0,
            &[
                &[23.3333333333],
                &[8.26598665578, 31.0295646002],
                &[4.26786615496, 12.9580862891, 37.7485177345],
            ],
        ),
        (
            100.0,
            45.0,
            &[
                &[30.0],
                &[11.2638377793, 35.7721734502],
                &[5.38185059889, 15.2028470752, 40.8113883008],
            ],
        ),
        (
            100.0,
            30.0,
            &[
                &[36.6666666667],
                &[15.0521237112, 40.5147823001],
                &[7.04012131641, 17.9580862891, 43.8742588672],
            ],
        ),
        (100.0, 0.0, &[&[50.0], &[25.0, 50.0], &[12.5, 25.0, 50.0]]),
        (
            800.0,
            90.0,
            &[&[28.2842712475], &[9.28317766723, 86.1773876013]],
        ),
        (
            800.0,
            60.0,
            &[&[152.189514165], &[37.9862726227, 190.784925068]],
        ),
        (
            800.0,
            45.0,
            &[&[214.142135624], &[65.4137622838, 243.088693801]],
        ),
        (
            800.0,
            30.0,
            &[&[276.094757082], &[101.558546734, 295.392462534]],
        ),
        (800.0, 0.0, &[&[400.0], &[200.0, 400.0]]),
    ];
    for (far, g, by_k) in table {
        let scheme = SplitScheme::Adaptive {
            delta: 2.0,
            gamma: deg(g),
        };
        for (interior, k) in by_k.iter().zip(2..) {
            let b = scheme.boundaries(range(1.0, far), k).unwrap();
            assert_eq!((b[0], b[k]), (1.0, far));
            for (x, y) in b[1..k].iter().zip(interior.iter()) {
                assert_ref(*x, *y, &format!("f = {far}, γ = {g}°, k = {k}"));
            }
        }
    }
}

#[test]
fn section_8_6_practical_split() {
    let table: [&[f64]; 3] = [
        &[30.25],
        &[19.3207944168, 44.2721734502],
        &[14.4561388301, 30.25, 53.4363883008],
    ];
    for (interior, k) in table.iter().zip(2..) {
        let b = SplitScheme::Practical { weight: 0.5 }
            .boundaries(range(1.0, 100.0), k)
            .unwrap();
        assert_eq!((b[0], b[k]), (1.0, 100.0));
        for (x, y) in b[1..k].iter().zip(interior.iter()) {
            assert_ref(*x, *y, &format!("practical λ = 0.5, k = {k}"));
        }
    }
}
