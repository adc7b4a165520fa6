//! The heat map: viridis at its control points, the logarithmic scale's documented positions,
//! monotone lightness, holes in grey, and the scale's validation.

use shadowlab_analysis::AnalysisError;
use shadowlab_analysis::classify::{
    BACKGROUND, CORRECT_LIT, CORRECT_SHADOW, FALSELY_LIT, FALSELY_SHADOWED,
};
use shadowlab_analysis::images::{
    CauseCounts, ClassCounts, HeatScale, NO_VALUE, VIRIDIS, colour, difference_legend,
    footprint_colour_bar, heatmap, value_range,
};

/// Relative luminance of an sRGB colour (ITU-R BT.709 weights on linearised channels).
fn luminance(c: [u8; 3]) -> f64 {
    let linear = |v: u8| {
        let v = f64::from(v) / 255.0;
        if v <= 0.04045 {
            v / 12.92
        } else {
            ((v + 0.055) / 1.055).powf(2.4)
        }
    };
    0.2126 * linear(c[0]) + 0.7152 * linear(c[1]) + 0.0722 * linear(c[2])
}

/// Claim: the map's ends and control points are viridis's published colours, and its lightness
/// rises strictly from end to end (it reads in greyscale).
#[test]
fn the_colour_map_is_viridis_and_rises_in_lightness() {
    assert_eq!(colour(0.0), [0x44, 0x01, 0x54]);
    assert_eq!(colour(1.0), [0xFD, 0xE7, 0x25]);
    assert_eq!(colour(4.0 / 9.0), [0x26, 0x82, 0x8E]);
    assert_eq!(colour(-3.0), colour(0.0));
    assert_eq!(colour(7.0), colour(1.0));
    let lightness: Vec<f64> = (0..=90)
        .map(|k| luminance(colour(f64::from(k) / 90.0)))
        .collect();
    assert!(lightness.windows(2).all(|w| w[0] < w[1]), "{lightness:?}");
}

/// Claim: on the 0.1–100 pixels-per-texel scale one pixel per texel sits at a third of the map and
/// ten at two thirds (the control points `#31688E` and `#35B779`); values beyond the ends clamp,
/// +∞ is the top, `None` and NaN are grey; rows keep their order (row 0 at the bottom in and out).
#[test]
fn the_scale_puts_values_where_documented() {
    let scale = HeatScale::PIXELS_PER_TEXEL;
    assert!((scale.fraction(1.0).unwrap() - 1.0 / 3.0).abs() < 1e-15);
    assert!((scale.fraction(10.0).unwrap() - 2.0 / 3.0).abs() < 1e-15);
    let values = [
        Some(1.0),
        Some(10.0),
        Some(0.01),
        Some(f64::INFINITY),
        None,
        Some(f64::NAN),
    ];
    assert_eq!(
        heatmap(&values, 3, 2, scale),
        [
            [0x31, 0x68, 0x8E],
            [0x35, 0xB7, 0x79],
            [0x44, 0x01, 0x54],
            [0xFD, 0xE7, 0x25],
            NO_VALUE,
            NO_VALUE
        ]
    );
}

/// Claim: a scale must be `0 < low < high < ∞`.
#[test]
fn bad_scales_are_errors() {
    assert!(HeatScale::log(1e-3, 1e3).is_ok());
    for (low, high) in [
        (0.0, 1.0),
        (-1.0, 1.0),
        (2.0, 1.0),
        (1.0, 1.0),
        (1.0, f64::INFINITY),
        (f64::NAN, 1.0),
    ] {
        assert!(
            matches!(
                HeatScale::log(low, high),
                Err(AnalysisError::HeatScale { .. })
            ),
            "{low}, {high}"
        );
    }
}

/// Claim: a heat map's range is its least and greatest finite value; holes, NaN and ∞ are not
/// values; the colour bar runs through viridis's control points on the footprint scale.
#[test]
fn the_range_and_the_colour_bar() {
    let values = [
        Some(3.0),
        None,
        Some(f64::NAN),
        Some(f64::INFINITY),
        Some(0.5),
        Some(2.0),
    ];
    assert_eq!(value_range(&values), Some((0.5, 3.0)));
    assert_eq!(value_range(&[None, Some(f64::NAN)]), None);
    let bar = footprint_colour_bar(Some((0.5, 3.0)));
    assert_eq!(
        (bar.low, bar.high, bar.range),
        (0.1, 100.0, Some((0.5, 3.0)))
    );
    let stops: Vec<[u8; 3]> = bar.stops.iter().map(|c| [c.0, c.1, c.2]).collect();
    assert_eq!(stops, VIRIDIS);
    for (k, stop) in stops.iter().enumerate() {
        #[expect(clippy::cast_precision_loss, reason = "ten stops")]
        let at = colour(k as f64 / 9.0);
        assert_eq!(at, *stop, "the bar's stop {k} is the map's colour there");
    }
}

/// Claim: the classes of a difference image are counted by colour, and the legend names each
/// with its colour and count, errors first.
#[test]
fn the_difference_classes_are_counted() {
    let image = [
        FALSELY_LIT,
        FALSELY_LIT,
        FALSELY_SHADOWED,
        CORRECT_LIT,
        CORRECT_SHADOW,
        CORRECT_SHADOW,
        BACKGROUND,
    ];
    let counts = ClassCounts::of(&image);
    assert_eq!(
        counts,
        ClassCounts {
            falsely_lit: 2,
            falsely_shadowed: 1,
            correct_lit: 1,
            correct_shadow: 2,
            background: 1,
        }
    );
    let legend = difference_legend(&counts);
    let labels: Vec<&str> = legend.iter().map(|s| s.label.as_str()).collect();
    assert_eq!(
        labels,
        [
            "falsely lit (light leak): 2 px",
            "falsely shadowed: 1 px",
            "correct, lit: 1 px",
            "correct, in shadow: 2 px",
            "nothing visible: 1 px"
        ]
    );
    let [r, g, b] = FALSELY_LIT;
    assert_eq!(legend[0].color, shadowlab_plot::Color(r, g, b));
}

/// Claim: the causes picture's colours are five distinct colours, none of them the difference
/// image's error colours or its greys and black, so the two pictures cannot be confused.
#[test]
fn the_causes_colours_are_their_own() {
    use shadowlab_analysis::attribution::Cause;
    let causes: Vec<[u8; 3]> = Cause::ALL.iter().map(|c| c.colour()).collect();
    for (k, colour) in causes.iter().enumerate() {
        assert!(!causes[..k].contains(colour), "{colour:?} repeated");
        for taken in [
            FALSELY_LIT,
            FALSELY_SHADOWED,
            CORRECT_LIT,
            CORRECT_SHADOW,
            BACKGROUND,
        ] {
            assert_ne!(*colour, taken, "{:?}", Cause::ALL[k]);
        }
    }
}

/// Claim: the causes picture's counts are the direct tally of its colours, on 1 and 3 threads,
/// over more pixels than one work item takes (and a partial last one); a colour of no class
/// counts nowhere.
#[test]
fn the_causes_are_counted_on_any_thread_count() {
    use shadowlab_analysis::attribution::Cause;
    let palette: Vec<[u8; 3]> = Cause::ALL
        .iter()
        .map(|c| c.colour())
        .chain([CORRECT_LIT, CORRECT_SHADOW, BACKGROUND, [1, 2, 3]])
        .collect();
    // Pixel k takes the colour its Fibonacci hash picks: every class, unevenly.
    let pixels: Vec<[u8; 3]> = (0..3 * (1_u64 << 14) + 777)
        .map(|k| {
            let pick = (k.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 40) % palette.len() as u64;
            palette[usize::try_from(pick).unwrap()]
        })
        .collect();
    let tally = |colour: [u8; 3]| pixels.iter().filter(|p| **p == colour).count() as u64;
    for threads in [1, 3] {
        let counts = crate::support::on_threads(threads, || CauseCounts::of(&pixels));
        for cause in Cause::ALL {
            assert_eq!(counts.first.of(cause), tally(cause.colour()), "{cause:?}");
        }
        assert_eq!(counts.correct_lit, tally(CORRECT_LIT));
        assert_eq!(counts.correct_shadow, tally(CORRECT_SHADOW));
        assert_eq!(counts.background, tally(BACKGROUND));
    }
    assert!(palette.iter().all(|&colour| tally(colour) > 0));
}
