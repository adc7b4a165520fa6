use serde_json::Value;

use crate::support::{shadowlab, stderr, stdout};

fn json(args: &[&str]) -> Value {
    let mut all = vec!["params", "--json"];
    all.extend_from_slice(args);
    let output = shadowlab(&all, None);
    assert!(output.status.success(), "{}", stderr(&output));
    serde_json::from_str(&stdout(&output)).expect("valid JSON")
}

fn number(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

#[track_caller]
fn assert_close(actual: f64, expected: f64) {
    assert!(
        (actual - expected).abs() <= 1e-10 * expected.abs(),
        "{actual} vs {expected}"
    );
}

#[test]
fn values_at_45_degrees_match_formulas_md() {
    let v = json(&[
        "--near", "1", "--far", "100", "--fov", "60", "--gamma", "45",
    ]);
    let t = &v["techniques"];
    // formulas.md §8.2–8.4, n = 1, f = 100, φ = 30°, γ = 45°.
    assert_close(number(&t["lispsm"]["n"]), 15.5563491861);
    assert_close(number(&t["lispsm"]["lambda"]), 0.139849135797);
    assert_close(number(&t["lispsm"]["max_error"]), 35.2076074809);
    assert_close(number(&t["lispsm_dz"]["n"]), 14.0361142587);
    assert_close(number(&t["cad"]["n"]), 7.36992630259);
    assert_eq!(t["cad"]["r"], "eq18");
    assert_close(number(&t["gmnpr"]["lambda"]), 0.0662544798897);
    assert_close(number(&t["gmnpr"]["max_error"]), 18.8584930442);
    assert_close(number(&t["minimax"]["lambda"]), 0.0662544798897);
    assert!(t["uniform"]["n"].is_null() && t["uniform"]["lambda"].is_null());
    assert!(number(&t["uniform"]["max_error"]) > number(&t["minimax"]["max_error"]));
    assert!(number(&t["glpr"]["lambda"]) > 0.0);
    assert_close(number(&v["gamma_lim"]), 30.4986768609);
    assert_close(number(&v["theta0"]), 27.6933585688);
    assert_close(number(&v["theta1"]), 28.9537861393);
    assert_eq!(v["not_defined"], serde_json::json!([]));
    assert_eq!(v["input"]["gamma"], 45.0);
}

#[test]
fn techniques_are_listed_in_a_fixed_order() {
    let args = [
        "params", "--json", "--near", "1", "--far", "100", "--fov", "60", "--gamma", "45",
    ];
    let text = stdout(&shadowlab(&args, None));
    let keys = [
        "uniform",
        "lispsm",
        "lispsm_dz",
        "cad",
        "gmnpr",
        "glpr",
        "minimax",
    ];
    let at: Vec<usize> = keys
        .iter()
        .map(|k| {
            text.find(&format!("\"{k}\": {{"))
                .unwrap_or_else(|| panic!("{k} missing"))
        })
        .collect();
    assert!(at.windows(2).all(|w| w[0] < w[1]), "{text}");
}

#[test]
fn glpr_is_left_out_below_half_the_fov() {
    let v = json(&[
        "--near", "1", "--far", "100", "--fov", "60", "--gamma", "20",
    ]);
    assert!(v["techniques"].get("glpr").is_none());
    assert_eq!(v["not_defined"], serde_json::json!(["glpr"]));
    assert_close(number(&v["techniques"]["minimax"]["n"]), 32.6755840999);
    assert_close(
        number(&v["techniques"]["gmnpr"]["max_error"]),
        440.145885628,
    );
}

#[test]
fn the_cad_fall_back_curve_is_selectable_and_named() {
    let v = json(&[
        "--near", "1", "--far", "100", "--fov", "60", "--gamma", "10", "--cad-r", "eq17",
    ]);
    assert_eq!(v["techniques"]["cad"]["r"], "eq17");
    assert_close(number(&v["techniques"]["cad"]["n"]), 10.3239340599);
}

#[test]
fn parallel_light_is_uniform_and_unbounded() {
    let v = json(&["--near", "1", "--far", "100", "--fov", "60", "--gamma", "0"]);
    for (key, t) in v["techniques"].as_object().unwrap() {
        assert!(t["n"].is_null() && t["lambda"].is_null(), "{key}: {t}");
        assert!(t["max_error"].is_null(), "{key}: {t}");
    }
}

#[test]
fn the_table_lists_every_defined_technique() {
    let output = shadowlab(
        &[
            "params", "--near", "1", "--far", "100", "--fov", "60", "--gamma", "20",
        ],
        None,
    );
    assert!(output.status.success());
    let text = stdout(&output);
    for key in ["uniform", "lispsm", "lispsm_dz", "cad", "gmnpr", "minimax"] {
        assert!(
            text.lines().any(|l| l.starts_with(key)),
            "{key} missing:\n{text}"
        );
    }
    assert!(text.contains("not defined at this angle: glpr"), "{text}");
    assert!(text.contains("440.145885628"), "{text}");
}

#[test]
fn bad_input_names_the_flag_and_exits_2() {
    let base = [
        "params", "--near", "1", "--far", "100", "--fov", "60", "--gamma", "45",
    ];
    let cases: [(&str, &str, &str); 7] = [
        ("--near", "0", "--near"),
        ("--near", "NaN", "--near"),
        ("--far", "0.5", "--far"),
        ("--fov", "180", "--fov"),
        ("--fov", "-5", "--fov"),
        ("--gamma", "91", "--gamma"),
        ("--gamma", "inf", "--gamma"),
    ];
    for (flag, value, named) in cases {
        let mut args = base.to_vec();
        let at = args.iter().position(|a| *a == flag).unwrap();
        args[at + 1] = value;
        let output = shadowlab(&args, None);
        assert_eq!(output.status.code(), Some(2), "{flag} {value}");
        let message = stderr(&output);
        assert!(message.contains(named), "{flag} {value}: {message}");
        assert!(stdout(&output).is_empty());
    }
    let output = shadowlab(&["params", "--near", "1"], None);
    assert_eq!(output.status.code(), Some(2));
    assert!(stderr(&output).contains("--far"));
}
