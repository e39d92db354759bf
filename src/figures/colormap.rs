//! The colour map of the cap coloured by `d_area` and its colour bar: a diverging map, blue
//! where a face's share of the area shrank on the cap (`d_area < 0`), white where it kept it,
//! red where it grew; symmetric about zero and saturated beyond a robust range, so that a
//! few extreme faces do not wash out the rest.

use super::encode::RgbImage;
use super::text::{draw_texts, Anchor, Label};
use super::FigureError;

/// Colour of faces without a value (the punctured quad's).
pub const NO_VALUE: [u8; 3] = [170, 170, 170];

/// Share of faces whose `|d_area|` is within the colour range; the rest saturate.
pub const RANGE_QUANTILE: f64 = 0.98;

/// Colour steps on each side of zero.
pub const STEPS: f64 = 8.0;

/// The colour of `t` in `[-1, 1]` (clamped): blue, white, red, in [`STEPS`] steps each side.
pub fn diverging(t: f64) -> [u8; 3] {
    let t = if t.is_finite() { t.clamp(-1.0, 1.0) } else { return NO_VALUE };
    let (cold, hot) = ([33.0, 102.0, 172.0], [178.0, 24.0, 43.0]);
    let end: [f64; 3] = if t < 0.0 { cold } else { hot };
    // In steps of 1 / STEPS: a colour reads as a value off the bar.
    let s = (t.abs() * STEPS).round() / STEPS;
    [0, 1, 2].map(|k| (255.0 + s * (end[k] - 255.0)).round() as u8)
}

/// The symmetric colour range `m` of `values`: the [`RANGE_QUANTILE`] quantile of the finite
/// `|values|` (a tiny positive number when they are all zero or there is none).
pub fn symmetric_range(values: &[f64]) -> f64 {
    let mut abs: Vec<f64> = values.iter().filter(|v| v.is_finite()).map(|v| v.abs()).collect();
    if abs.is_empty() {
        return 1e-12;
    }
    abs.sort_by(f64::total_cmp);
    let k = ((RANGE_QUANTILE * (abs.len() - 1) as f64).round() as usize).min(abs.len() - 1);
    abs[k].max(1e-12)
}

/// Width of the colour-bar strip added to the right of the views.
pub const BAR_STRIP: u32 = 110;

/// `image` with a colour bar strip on its right: the map from `-range` to `range`, with
/// the ends and zero labelled, and `label` above.
pub fn with_colour_bar(image: &RgbImage, range: f64, label: &str, figure: &str) -> Result<RgbImage, FigureError> {
    let mut out = RgbImage::filled(image.width + BAR_STRIP, image.height, [255, 255, 255]);
    out.paste(image, 0, 0);
    let (x0, bar_w) = (image.width + 14, 18u32);
    let (top, bottom) = (50u32, image.height.saturating_sub(14));
    if bottom <= top + 10 {
        return Err(FigureError::Empty { figure: figure.to_string(), why: format!("the image ({} px high) is too small for a colour bar", image.height) });
    }
    for y in top..bottom {
        let t = 1.0 - 2.0 * f64::from(y - top) / f64::from(bottom - 1 - top);
        let t = (t * STEPS).round() / STEPS;
        let c = diverging(t);
        for x in x0..x0 + bar_w {
            let at = 3 * (y * out.width + x) as usize;
            out.pixels[at..at + 3].copy_from_slice(&c);
        }
    }
    let tx = (x0 + bar_w + 6) as i32;
    let labels = [
        Label::new(label, (x0 as i32 - 4, 24), 15, Anchor::TopLeft),
        Label::new(&format!("{range:+.3}"), (tx, top as i32), 13, Anchor::MiddleLeft),
        Label::new("0", (tx, ((top + bottom) / 2) as i32), 13, Anchor::MiddleLeft),
        Label::new(&format!("{:+.3}", -range), (tx, bottom as i32 - 1), 13, Anchor::MiddleLeft),
    ];
    draw_texts(&mut out, &labels, figure)?;
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn map_ends_and_middle() {
        assert_eq!(diverging(0.0), [255, 255, 255]);
        assert_eq!(diverging(-1.0), [33, 102, 172]);
        assert_eq!(diverging(5.0), [178, 24, 43]);
        assert_eq!(diverging(f64::NAN), NO_VALUE);
        let v: Vec<f64> = (0..=100).map(|i| f64::from(i) / 100.0).chain([f64::NAN, -50.0]).collect();
        assert!((symmetric_range(&v) - 0.98).abs() < 0.011, "{}", symmetric_range(&v));
    }
}
