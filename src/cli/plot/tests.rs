//! The charts drawn from small data: their bytes, ticks, legends and gaps.

use super::chart::{decimals, fixed, power};
use super::sketch::Sketch;
use super::style::{LEGEND_TEXT, SMALLEST_TEXT, rgb};
use super::*;

/// Names, titles and values with characters that XML escapes.
const TITLES: Titles<'static> = Titles {
    title: "A chart <of> things",
    x: "time (seconds)",
    y: "best & worst",
};

/// Whether `svg` holds `text` as the text of an element (escaped as XML escapes it).
fn holds(svg: &str, text: &str) -> bool {
    let escaped = text
        .replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;");
    svg.contains(&format!(">\n{escaped}\n<")) || svg.contains(&format!(">{escaped}\n<"))
}

/// Checks that `figure` is `size` pixels, not blank, and that its SVG holds the
/// titles and every name in `legend`.
fn check(figure: &Figure, size: (u32, u32), legend: &[&str]) {
    assert_eq!(figure.png.dimensions(), size);
    assert!(
        figure.png.pixels().any(|p| p.0 != [255, 255, 255]),
        "a blank picture"
    );
    let svg = &figure.svg;
    assert!(svg.starts_with("<svg"), "{svg}");
    for text in [TITLES.title, TITLES.x, TITLES.y].iter().chain(legend) {
        assert!(holds(svg, text), "no `{text}` in the SVG:\n{svg}");
    }
}

#[test]
fn curves_name_every_line() {
    let x = [0.0, 1.0, 2.0, 3.0];
    let lines = [
        Line {
            name: "best",
            colour: palette(0),
            values: &[1.0, 2.0, 2.5, 3.0],
        },
        Line {
            name: "mean",
            colour: palette(1),
            values: &[0.5, f64::NAN, 1.5, 2.0],
        },
    ];
    let figure = curves((640, 400), &TITLES, &x, &lines).unwrap();
    check(&figure, (640, 400), &["best", "mean"]);
}

#[test]
fn bands_name_every_band_and_their_shading() {
    let bands_ = [Band {
        name: "population=40",
        colour: palette(2),
        mean: &[1.0, 2.0, 3.0],
        std: &[0.1, f64::NAN, 0.3],
    }];
    let figure = bands((800, 500), &TITLES, 300.0, &bands_).unwrap();
    check(
        &figure,
        (800, 500),
        &["population=40", "line: mean, shaded: mean +- std"],
    );
}

#[test]
fn spreads_on_a_log_scale_write_powers_of_ten() {
    let spread = Spread {
        name: "ga",
        colour: palette(0),
        centre: &[1.0, 0.1, 0.01, 0.0],
        low: &[0.5, 0.05, 0.005, -1.0],
        high: &[2.0, 0.2, 0.02, 0.001],
    };
    let key = "line: median, shaded: quartiles";
    let figure = spreads((800, 500), &TITLES, 2.0, &[spread], YScale::Log, key).unwrap();
    check(&figure, (800, 500), &["ga", key]);
    for decade in ["1e-3", "1e-2", "1e-1", "1e0"] {
        assert!(holds(&figure.svg, decade), "no tick {decade}");
    }
}

#[test]
fn error_bars_name_their_x_values_and_bands() {
    let names = ["tournament_roulette", "tournament", "roulette", "random"].map(String::from);
    let bands_ = [
        Band {
            name: "population=20",
            colour: palette(0),
            mean: &[1.0, 2.0, f64::NAN, 1.5],
            std: &[0.5, 0.0, 0.0, 0.25],
        },
        Band {
            name: "population=40",
            colour: palette(1),
            mean: &[1.5, 2.5, 1.0, 2.0],
            std: &[0.5, f64::INFINITY, 0.0, 0.25],
        },
    ];
    let figure = error_bars((800, 500), &TITLES, &XValues::Names(&names), &bands_).unwrap();
    let mut legend = vec!["population=20", "population=40", ErrorBars::KEY];
    legend.extend(names.iter().map(String::as_str));
    check(&figure, (800, 500), &legend);
    let numbers = error_bars(
        (800, 500),
        &TITLES,
        &XValues::Numbers(&[10.0, 20.0, 50.0, 100.0]),
        &bands_,
    )
    .unwrap();
    check(&numbers, (800, 500), &["population=20", ErrorBars::KEY]);
}

#[test]
fn scatter_names_its_points() {
    let points = [(1.0, 2.0), (2.0, f64::NAN), (3.0, 1.0)];
    let figure = scatter((640, 480), &TITLES, &points, palette(0), "front").unwrap();
    check(&figure, (640, 480), &["front"]);
}

#[test]
fn empty_and_non_finite_data_still_make_a_chart() {
    let nothing: [f64; 0] = [];
    let nan = [f64::NAN; 3];
    let figures = [
        curves((640, 400), &TITLES, &nothing, &[]).unwrap(),
        curves(
            (640, 400),
            &TITLES,
            &nan,
            &[Line {
                name: "best",
                colour: palette(0),
                values: &nan,
            }],
        )
        .unwrap(),
        bands((800, 500), &TITLES, f64::NAN, &[]).unwrap(),
        spreads(
            (800, 500),
            &TITLES,
            0.0,
            &[Spread {
                name: "ga",
                colour: palette(0),
                centre: &nan,
                low: &nan,
                high: &[0.0; 3],
            }],
            YScale::Log,
            "shaded",
        )
        .unwrap(),
        error_bars((800, 500), &TITLES, &XValues::Names(&[]), &[]).unwrap(),
        error_bars(
            (800, 500),
            &TITLES,
            &XValues::Numbers(&nan),
            &[Band {
                name: "all",
                colour: palette(0),
                mean: &nan,
                std: &nan,
            }],
        )
        .unwrap(),
        scatter((640, 480), &TITLES, &[(f64::NAN, 1.0)], palette(0), "front").unwrap(),
    ];
    for figure in &figures {
        assert!(holds(&figure.svg, TITLES.title));
    }
}

#[test]
fn the_same_data_give_the_same_bytes() {
    let draw = || {
        let lines = [Line {
            name: "best",
            colour: palette(0),
            values: &[1.0, 2.0, 4.0],
        }];
        curves((640, 400), &TITLES, &[0.0, 1.0, 2.0], &lines).unwrap()
    };
    let (a, b) = (draw(), draw());
    assert_eq!(a.png, b.png);
    assert_eq!(a.svg, b.svg);
}

#[test]
fn the_legend_keeps_out_of_the_data() {
    // A falling line ends in the bottom right corner, where the legend would go.
    let values: Vec<f64> = (0..50).map(|i| 50.0 - f64::from(i)).collect();
    let x: Vec<f64> = (0..50).map(f64::from).collect();
    let line = [Line {
        name: "falling",
        colour: palette(2),
        values: &values,
    }];
    let figure = curves((640, 400), &TITLES, &x, &line).unwrap();
    // The legend's box is drawn in the top right, bottom left or top left: its
    // border passes near one of those corners of the plot area, never the bottom
    // right, where the line's last pixels stay visible.
    let ink = rgb(palette(2));
    let (w, h) = figure.png.dimensions();
    let coloured = |x0: u32, y0: u32, x1: u32, y1: u32| {
        (y0..y1).any(|y| {
            (x0..x1).any(|x| {
                let p = figure.png.get_pixel(x, y).0;
                p == [ink.0, ink.1, ink.2]
            })
        })
    };
    assert!(
        coloured(w - 60, h - 90, w - 20, h - 50),
        "the line's end is hidden"
    );
}

#[test]
fn tick_values_have_the_decimals_their_step_needs() {
    assert_eq!(decimals(&(0.0..300.0)), 0);
    assert_eq!(decimals(&(0.0..2.0)), 1);
    assert_eq!(decimals(&(1.5..1.6)), 2);
    assert_eq!(decimals(&(1.0..1.0)), 0);
    let one = fixed(1);
    assert_eq!(one(&0.30000000000000004), "0.3");
    assert_eq!(one(&-0.01), "0.0");
    assert_eq!(one(&-0.5), "-0.5");
    assert_eq!(power(&0.001), "1e-3");
}

#[test]
fn a_long_legend_shrinks_to_fit_the_plot_area() {
    register().unwrap();
    let sketch = Sketch {
        names: vec!["a".repeat(200)],
        ink: Vec::new(),
    };
    let room = sketch.legend_size(LEGEND_TEXT).unwrap().0 * 3 / 4;
    let size = sketch.legend_text(room).unwrap();
    assert!((SMALLEST_TEXT..LEGEND_TEXT).contains(&size), "{size}");
    assert!(sketch.legend_size(size).unwrap().0 <= room + 2);
    assert_eq!(sketch.legend_text(10_000).unwrap(), LEGEND_TEXT);
}

#[test]
fn a_label_is_drawn_in_the_corner() {
    let mut image = RgbImage::from_pixel(64, 64, Rgb([0, 0, 0]));
    label(&mut image, "12").unwrap();
    // The white box behind the text, and dark text on it.
    assert_eq!(image.get_pixel(1, 1).0, [255, 255, 255]);
    let inked = (0..24).any(|y| (0..32).any(|x| image.get_pixel(x, y).0[0] < 128));
    assert!(inked);
    assert_eq!(image.get_pixel(60, 60).0, [0, 0, 0]);
}
