//! PNG particle maps: a scalar particle field (e.g. the effective plastic strain on a section of
//! a Taylor bar) drawn as touching square markers in an equal-aspect frame, coloured with
//! viridis, with a colour bar, axis ticks, optional outline polylines and a one-line legend
//! above the plot (so it never hides particles).
//!
//! Pixels are written straight into an RGB buffer: markers are pixel-aligned rectangles (so
//! particles one `marker_size` apart share an edge without gaps) and outlines are anti-aliased
//! here, over a thin white halo so they read on dark and light colours alike. Text, tick labels, [`PlotError`] and the atomic PNG write are shared with
//! [`crate::plot`], which re-exports this module's public items. The output is deterministic:
//! the same spec always gives the same bytes.
//!
//! Setting `TLSPH_PLOT_SAMPLES=<dir>` while running this module's tests also copies a sample map
//! (`particle_map_sample.png`) into `<dir>` for a visual check.

use std::path::Path;

use plotters::coord::ranged1d::BoldPoints;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::{RGBColor, Ranged};

use crate::plot::{
    blend, tick_label, trim_number, write_atomically, Axis, HAlign, PlotError, TextJob,
    TextPainter, VAlign, AXIS_DESC_FONT_PX, LEGEND_FONT_PX, LEGEND_SAMPLE_PX, N_TICK_LABELS,
    TEXT_COLOR, TICK_FONT_PX, TITLE_FONT_PX,
};

/// Width of a particle map, in pixels; only tall domains (capped by [`MAP_MAX_HEIGHT`]) give a
/// narrower image.
pub const MAP_WIDTH: u32 = 900;
/// Smallest height of a particle map, in pixels (wide, flat domains).
pub const MAP_MIN_HEIGHT: u32 = 400;
/// Largest height of a particle map, in pixels (tall, slender domains).
pub const MAP_MAX_HEIGHT: u32 = 1400;
/// Smallest width of a particle map, in pixels (tall, slender domains).
pub const MAP_MIN_WIDTH: u32 = 520;

/// Marker edge length, in pixels, when [`ParticleMapSpec::marker_size`] is not a positive number.
pub const DEFAULT_MARKER_PX: f64 = 3.0;

/// Colour of particles whose value is NaN or infinite.
const NAN_COLOR: [u8; 3] = [160, 160, 160];
/// Frame, tick marks and colour-bar border.
const FRAME_COLOR: [u8; 3] = [38, 38, 38];
/// Outline colours, cycled: red, near-black, orange, cyan (all visible on viridis).
const OUTLINE_COLORS: [RGBColor; 4] = [
    RGBColor(214, 39, 40),
    RGBColor(20, 20, 20),
    RGBColor(255, 127, 14),
    RGBColor(23, 190, 207),
];
/// Half of the outline stroke width, pixels.
const OUTLINE_HALF_WIDTH: f64 = 1.1;
/// Half width of the white halo under each outline, pixels.
const HALO_HALF_WIDTH: f64 = 2.6;
/// Opacity of the halo.
const HALO_ALPHA: f32 = 0.85;
/// Empty margin around the data, as a fraction of the larger data extent (same on both axes).
const DATA_PAD: f64 = 0.04;
const TICK_LEN: i32 = 5;
const TICK_GAP: i32 = 6;
/// Gap between the plotting area and the colour bar.
const CB_GAP: i32 = 24;
/// Width of the colour bar.
const CB_WIDTH: i32 = 18;
/// Height of one legend row.
const LEGEND_ROW_H: i32 = 22;
/// Horizontal gap between legend entries in a row.
const LEGEND_ITEM_GAP: i32 = 28;

/// Viridis (matplotlib's default colour map, CC0, van der Walt & Smith) sampled from its
/// published 256-entry table at entries 0, 16, ..., 240, 255: `(entry, r, g, b)`.
const VIRIDIS: [(u8, f64, f64, f64); 17] = [
    (0, 0.267004, 0.004874, 0.329415),
    (16, 0.282327, 0.094955, 0.417331),
    (32, 0.278826, 0.175490, 0.483397),
    (48, 0.258965, 0.251537, 0.524736),
    (64, 0.229739, 0.322361, 0.545706),
    (80, 0.199430, 0.387607, 0.554642),
    (96, 0.172719, 0.448791, 0.557885),
    (112, 0.149039, 0.508051, 0.557250),
    (128, 0.127568, 0.566949, 0.550556),
    (144, 0.120638, 0.625828, 0.533488),
    (160, 0.157851, 0.683765, 0.501686),
    (176, 0.246070, 0.738910, 0.452024),
    (192, 0.369214, 0.788888, 0.382914),
    (208, 0.515992, 0.831158, 0.294279),
    (224, 0.678489, 0.863742, 0.189503),
    (240, 0.845561, 0.887322, 0.099702),
    (255, 0.993248, 0.906157, 0.143936),
];

/// The viridis colour (8-bit sRGB) at `t` in `[0, 1]` (clamped), linearly interpolated between
/// 17 anchors of the published table; NaN gives the grey used for missing values.
pub fn viridis(t: f64) -> [u8; 3] {
    if t.is_nan() {
        return NAN_COLOR;
    }
    let pos = 255.0 * t.clamp(0.0, 1.0);
    let seg = VIRIDIS
        .windows(2)
        .position(|w| pos <= f64::from(w[1].0))
        .unwrap_or(VIRIDIS.len() - 2);
    let (a, b) = (VIRIDIS[seg], VIRIDIS[seg + 1]);
    let w = (pos - f64::from(a.0)) / f64::from(b.0 - a.0);
    let mix = |p: f64, q: f64| ((p + (q - p) * w) * 255.0).round().clamp(0.0, 255.0) as u8;
    [mix(a.1, b.1), mix(a.2, b.2), mix(a.3, b.3)]
}

/// One particle of a map: position in the plot plane and the value to colour it by.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MapPoint {
    /// Horizontal position, data units. Particles with a non-finite position are skipped.
    pub x: f64,
    /// Vertical position, data units.
    pub y: f64,
    /// Value mapped to the colour; NaN or infinite values are drawn grey.
    pub value: f64,
}

impl MapPoint {
    /// Convenience constructor.
    pub fn new(x: f64, y: f64, value: f64) -> Self {
        Self { x, y, value }
    }
}

/// A whole particle map.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ParticleMapSpec {
    /// Caption above the map (may be empty).
    pub title: String,
    /// Text under the x axis.
    pub x_label: String,
    /// Text beside the y axis.
    pub y_label: String,
    /// Label of the colour bar (field name and unit).
    pub value_label: String,
    /// Colour range; None = data min..max (ignoring non-finite values). Values outside the range
    /// get the end colours; a range with a non-finite end falls back to the data range; equal
    /// ends are widened. A reversed range `(hi, lo)` reverses the colour map.
    pub range: Option<(f64, f64)>,
    /// Marker size in data units (e.g. the particle spacing), so neighbouring particles touch.
    /// Markers are at least one pixel; a zero, negative or non-finite size (unknown spacing)
    /// gives dots of [`DEFAULT_MARKER_PX`] pixels.
    pub marker_size: f64,
    /// The particles, drawn in order (later ones on top).
    pub points: Vec<MapPoint>,
    /// Optional outline polylines drawn on top (e.g. a reference shape), each with a label for
    /// the legend above the plot (an empty label gives no legend entry). Non-finite vertices
    /// break the line. Outlines count towards the shown data range.
    pub outlines: Vec<(String, Vec<(f64, f64)>)>,
}

/// Writes `spec` as a PNG map to `path` (parent directories are created; the image goes to a
/// temporary file in the same directory first and is then renamed over `path`).
///
/// Both axes use the same scale (one data unit is the same number of pixels horizontally and
/// vertically). The image is [`MAP_WIDTH`] pixels wide and as tall as the data's aspect ratio
/// needs, within [`MAP_MIN_HEIGHT`]..=[`MAP_MAX_HEIGHT`]; a tall domain hitting the height cap
/// gives a narrower image (at least [`MAP_MIN_WIDTH`]), and any spare room widens the shown data
/// range instead of distorting it. Particles with a non-finite value are drawn grey and listed
/// in the legend.
///
/// Errors: [`PlotError::NoData`] when no particle has a finite position (nothing is written);
/// [`PlotError::Io`] / [`PlotError::Backend`] naming the path when rendering or writing fails.
pub fn write_particle_map(path: &Path, spec: &ParticleMapSpec) -> Result<(), PlotError> {
    let backend_err = |msg: String| PlotError::Backend(format!("{}: {msg}", path.display()));
    if !spec.points.iter().any(|p| finite_pos(p.x, p.y)) {
        return Err(PlotError::NoData {
            path: path.to_path_buf(),
        });
    }
    let painter = TextPainter::new().map_err(backend_err)?;
    let layout = Layout::new(spec, &painter).ok_or_else(|| PlotError::NoData {
        path: path.to_path_buf(),
    })?;
    let canvas = render(spec, &layout, &painter);
    write_atomically(path, &canvas.pixels, canvas.width, canvas.height)
}

fn finite_pos(x: f64, y: f64) -> bool {
    x.is_finite() && y.is_finite()
}

/// Marker edge length in data units (0 = unknown: [`DEFAULT_MARKER_PX`] dots).
fn marker_size(spec: &ParticleMapSpec) -> f64 {
    if spec.marker_size.is_finite() && spec.marker_size > 0.0 {
        spec.marker_size
    } else {
        0.0
    }
}

/// Colour range: explicit if usable, else the finite data values' min..max; widened if empty.
fn colour_range(spec: &ParticleMapSpec) -> (f64, f64) {
    let (lo, hi) = match spec.range {
        Some((a, b)) if a.is_finite() && b.is_finite() => (a, b),
        _ => {
            let mut lo = f64::INFINITY;
            let mut hi = f64::NEG_INFINITY;
            for p in spec.points.iter().filter(|p| finite_pos(p.x, p.y)) {
                if p.value.is_finite() {
                    lo = lo.min(p.value);
                    hi = hi.max(p.value);
                }
            }
            if lo <= hi {
                (lo, hi)
            } else {
                (0.0, 1.0)
            }
        }
    };
    if lo == hi {
        let d = if lo == 0.0 { 1.0 } else { 0.1 * lo.abs() };
        (lo - d, hi + d)
    } else {
        (lo, hi)
    }
}

/// Position of `v` in the colour range, NaN for non-finite values (drawn grey).
fn colour_fraction(range: (f64, f64), v: f64) -> f64 {
    if v.is_finite() {
        ((v - range.0) / (range.1 - range.0)).clamp(0.0, 1.0)
    } else {
        f64::NAN
    }
}

/// Colour-bar label for `v`: plain decimals resolving a thousandth of the range span, or three
/// significant digits in `1.25e8` style for very large or small magnitudes.
fn value_text(range: (f64, f64), v: f64) -> String {
    let span = (0.5 * range.1 - 0.5 * range.0).abs() * 2.0;
    if v.abs() <= 1e-9 * span {
        return "0".to_string();
    }
    let step_exp = span.log10().floor() as i32 - 2;
    let max_abs = range.0.abs().max(range.1.abs());
    if !(1e-3..1e5).contains(&max_abs) {
        trim_number(&format!("{v:.2e}"))
    } else {
        let decimals = (-step_exp).clamp(0, 12) as usize;
        trim_number(&format!("{v:.decimals$}"))
    }
}

/// Tick label with a typographic minus sign.
fn minus(text: &str) -> String {
    text.replace('-', "\u{2212}")
}

/// Nice tick values inside `axis` (the points plotters would mark), with their labels.
fn ticks(axis: &Axis, n: usize) -> Vec<(f64, String)> {
    RangedCoordf64::from(axis.lo..axis.hi)
        .key_points(BoldPoints(n))
        .into_iter()
        .map(|v| (v, minus(&tick_label(axis, v))))
        .collect()
}

fn widest(painter: &TextPainter, labels: &[(f64, String)], px: f64) -> f32 {
    labels
        .iter()
        .map(|(_, t)| painter.width(t, px as f32))
        .fold(0.0f32, f32::max)
}

/// Image size, plotting area and axis ranges of one map.
#[derive(Debug, Clone)]
struct Layout {
    width: u32,
    height: u32,
    /// Plotting area: pixels `left..left + pw` by `top..top + ph`.
    left: i32,
    top: i32,
    pw: i32,
    ph: i32,
    x: Axis,
    y: Axis,
    /// Pixels per data unit, on both axes.
    scale: f64,
    x_ticks: Vec<(f64, String)>,
    y_ticks: Vec<(f64, String)>,
    colour: (f64, f64),
    /// Colour-bar labels at fractions 0, 0.5, 1 of the range.
    cb_ticks: Vec<(f64, String)>,
    cb_label_w: f32,
    /// Left edge of the colour bar.
    cb_left: i32,
    /// Legend rows (entry and its width in pixels), centred above the plot.
    legend_rows: Vec<Vec<(Entry, i32)>>,
    /// Bottom of the title band, top of the first legend row.
    legend_top: i32,
}

impl Layout {
    fn new(spec: &ParticleMapSpec, painter: &TextPainter) -> Option<Self> {
        if !spec.points.iter().any(|p| finite_pos(p.x, p.y)) {
            return None;
        }
        let half = 0.5 * marker_size(spec);
        let mut bounds: Option<[f64; 4]> = None;
        let mut extend = |x0: f64, x1: f64, y0: f64, y1: f64| {
            let b = bounds.get_or_insert([x0, x1, y0, y1]);
            *b = [b[0].min(x0), b[1].max(x1), b[2].min(y0), b[3].max(y1)];
        };
        for p in spec.points.iter().filter(|p| finite_pos(p.x, p.y)) {
            extend(p.x - half, p.x + half, p.y - half, p.y + half);
        }
        for (_, line) in &spec.outlines {
            for &(x, y) in line.iter().filter(|p| finite_pos(p.0, p.1)) {
                extend(x, x, y, y);
            }
        }
        let [xmin, xmax, ymin, ymax] = bounds?;
        let (cx, cy) = (0.5 * xmin + 0.5 * xmax, 0.5 * ymin + 0.5 * ymax);
        let (mut ex, mut ey) = (xmax - xmin, ymax - ymin);
        let mut span = ex.max(ey);
        if !(span > 0.0 && span.is_finite()) {
            let mag = cx.abs().max(cy.abs());
            span = if mag > 0.0 && mag.is_finite() {
                0.2 * mag
            } else {
                1.0
            };
        }
        ex = ex.max(1e-3 * span) + 2.0 * DATA_PAD * span;
        ey = ey.max(1e-3 * span) + 2.0 * DATA_PAD * span;

        let colour = colour_range(spec);
        let cb_ticks: Vec<(f64, String)> = [
            (0.0, colour.0),
            (0.5, 0.5 * colour.0 + 0.5 * colour.1),
            (1.0, colour.1),
        ]
        .into_iter()
        .map(|(t, v)| (t, minus(&value_text(colour, v))))
        .collect();
        let cb_label_w = widest(painter, &cb_ticks, TICK_FONT_PX);

        // Legend band between the title and the plot: entries side by side, wrapped into rows
        // that fit the narrowest image.
        let legend_rows = legend_rows(spec, painter);
        let title_band = if spec.title.is_empty() { 12 } else { 44 };
        let legend_top = title_band;
        let top = if legend_rows.is_empty() {
            title_band + 4
        } else {
            legend_top + LEGEND_ROW_H * legend_rows.len() as i32 + 8
        };
        let bottom = TICK_LEN + TICK_GAP + TICK_FONT_PX as i32 + 14 + AXIS_DESC_FONT_PX as i32 + 12;
        let value_band = if spec.value_label.is_empty() {
            0
        } else {
            14 + AXIS_DESC_FONT_PX as i32
        };
        let right =
            CB_GAP + CB_WIDTH + TICK_LEN + TICK_GAP + cb_label_w.ceil() as i32 + value_band + 16;
        let title_w = painter.width(&spec.title, TITLE_FONT_PX as f32).ceil() as i32;
        let min_width = (MAP_MIN_WIDTH as i32)
            .max(title_w + 40)
            .min(MAP_WIDTH as i32);
        let (min_h, max_h) = (MAP_MIN_HEIGHT as i32, MAP_MAX_HEIGHT as i32);

        // The left band depends on the y tick labels, which depend on the y range, which
        // depends on the left band: iterate to a fixed point (it settles in one or two rounds).
        let mut y_tick_w = 0.0f32;
        let mut layout = None;
        for _ in 0..4 {
            let left =
                14 + AXIS_DESC_FONT_PX as i32 + 12 + y_tick_w.ceil() as i32 + TICK_GAP + TICK_LEN;
            let avail_w = (MAP_WIDTH as i32 - left - right).max(120);
            let natural_ph = f64::from(avail_w) * ey / ex;
            let (width, pw, ph);
            if f64::from(top + bottom) + natural_ph > f64::from(max_h) {
                ph = max_h - top - bottom;
                let needed = (f64::from(ph) * ex / ey).round() as i32;
                width = (left + needed + right).max(min_width);
                pw = (width - left - right).max(1);
            } else {
                ph = (natural_ph.round() as i32).max(min_h - top - bottom);
                width = (left + avail_w + right).max(min_width);
                pw = width - left - right;
            }
            let height = top + ph + bottom;
            let scale = (f64::from(pw) / ex).min(f64::from(ph) / ey);
            let half_w = 0.5 * f64::from(pw) / scale;
            let half_h = 0.5 * f64::from(ph) / scale;
            let x = Axis {
                lo: cx - half_w,
                hi: cx + half_w,
                log: false,
            };
            let y = Axis {
                lo: cy - half_h,
                hi: cy + half_h,
                log: false,
            };
            let n_y = N_TICK_LABELS.min((ph / 45).max(2) as usize);
            let y_ticks = ticks(&y, n_y);
            let new_w = widest(painter, &y_ticks, TICK_FONT_PX);
            // Fewer x labels when long labels would not fit side by side.
            let mut n_x = N_TICK_LABELS;
            let mut x_ticks = ticks(&x, n_x);
            while n_x > 2 {
                let w = widest(painter, &x_ticks, TICK_FONT_PX);
                if (w + 14.0) * x_ticks.len() as f32 <= pw as f32 {
                    break;
                }
                n_x -= 1;
                x_ticks = ticks(&x, n_x);
            }
            let stable = new_w.ceil() <= y_tick_w.ceil();
            layout = Some(Layout {
                width: width as u32,
                height: height as u32,
                left,
                top,
                pw,
                ph,
                x,
                y,
                scale,
                x_ticks,
                y_ticks,
                colour,
                cb_ticks: cb_ticks.clone(),
                cb_label_w,
                cb_left: left + pw + CB_GAP,
                legend_rows: legend_rows.clone(),
                legend_top,
            });
            if stable {
                break;
            }
            y_tick_w = new_w;
        }
        layout
    }

    /// Continuous pixel coordinates of a data point (pixel `i` covers `i..i + 1`).
    fn to_px(&self, x: f64, y: f64) -> (f64, f64) {
        (
            f64::from(self.left) + (x - self.x.lo) * self.scale,
            f64::from(self.top) + (self.y.hi - y) * self.scale,
        )
    }

    fn plot_clip(&self) -> Clip {
        Clip {
            x0: self.left,
            y0: self.top,
            x1: self.left + self.pw,
            y1: self.top + self.ph,
        }
    }
}

/// A pixel rectangle `x0..x1` by `y0..y1` (exclusive ends).
#[derive(Debug, Clone, Copy)]
struct Clip {
    x0: i32,
    y0: i32,
    x1: i32,
    y1: i32,
}

/// Tightly packed RGB pixel buffer.
struct Canvas {
    pixels: Vec<u8>,
    width: u32,
    height: u32,
}

impl Canvas {
    fn new(width: u32, height: u32) -> Self {
        Self {
            pixels: vec![255; 3 * width as usize * height as usize],
            width,
            height,
        }
    }

    /// Fills `r` (clipped to the image) with `color`.
    fn fill(&mut self, r: Clip, color: [u8; 3]) {
        let x0 = r.x0.clamp(0, self.width as i32) as usize;
        let x1 = r.x1.clamp(0, self.width as i32) as usize;
        let y0 = r.y0.clamp(0, self.height as i32) as usize;
        let y1 = r.y1.clamp(0, self.height as i32) as usize;
        let w = self.width as usize;
        for row in y0..y1 {
            for px in self.pixels[3 * (row * w + x0)..3 * (row * w + x1)].chunks_exact_mut(3) {
                px.copy_from_slice(&color);
            }
        }
    }

    /// One-pixel rectangle border just inside `r`.
    fn border(&mut self, r: Clip, color: [u8; 3]) {
        self.fill(Clip { y1: r.y0 + 1, ..r }, color);
        self.fill(Clip { y0: r.y1 - 1, ..r }, color);
        self.fill(Clip { x1: r.x0 + 1, ..r }, color);
        self.fill(Clip { x0: r.x1 - 1, ..r }, color);
    }

    /// Anti-aliased polyline through `pts` (pixel coordinates) with round joins and caps,
    /// `2 * half_width` pixels wide, clipped to `clip`. A single point gives a round dot.
    fn stroke(
        &mut self,
        pts: &[(f64, f64)],
        half_width: f64,
        color: RGBColor,
        alpha: f32,
        clip: Clip,
    ) {
        if pts.is_empty() {
            return;
        }
        let reach = half_width + 1.0;
        let fold = |f: fn(f64, f64) -> f64, init: f64, sel: fn(&(f64, f64)) -> f64| {
            pts.iter().map(sel).fold(init, f)
        };
        let bx0 = ((fold(f64::min, f64::INFINITY, |p| p.0) - reach).floor() as i32).max(clip.x0);
        let bx1 = ((fold(f64::max, f64::NEG_INFINITY, |p| p.0) + reach).ceil() as i32).min(clip.x1);
        let by0 = ((fold(f64::min, f64::INFINITY, |p| p.1) - reach).floor() as i32).max(clip.y0);
        let by1 = ((fold(f64::max, f64::NEG_INFINITY, |p| p.1) + reach).ceil() as i32).min(clip.y1);
        if bx0 >= bx1 || by0 >= by1 {
            return;
        }
        let bw = (bx1 - bx0) as usize;
        let mut coverage = vec![0.0f32; bw * (by1 - by0) as usize];
        let segments: Vec<((f64, f64), (f64, f64))> = if pts.len() == 1 {
            vec![(pts[0], pts[0])]
        } else {
            pts.windows(2).map(|w| (w[0], w[1])).collect()
        };
        for (a, b) in segments {
            let sx0 = ((a.0.min(b.0) - reach).floor() as i32).max(bx0);
            let sx1 = ((a.0.max(b.0) + reach).ceil() as i32).min(bx1);
            let sy0 = ((a.1.min(b.1) - reach).floor() as i32).max(by0);
            let sy1 = ((a.1.max(b.1) + reach).ceil() as i32).min(by1);
            let (dx, dy) = (b.0 - a.0, b.1 - a.1);
            let len2 = dx * dx + dy * dy;
            for y in sy0..sy1 {
                for x in sx0..sx1 {
                    let (px, py) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
                    let t = if len2 > 0.0 {
                        (((px - a.0) * dx + (py - a.1) * dy) / len2).clamp(0.0, 1.0)
                    } else {
                        0.0
                    };
                    let d = (px - a.0 - t * dx).hypot(py - a.1 - t * dy);
                    let c = (half_width + 0.5 - d).clamp(0.0, 1.0) as f32;
                    let cell = &mut coverage[(y - by0) as usize * bw + (x - bx0) as usize];
                    *cell = cell.max(c);
                }
            }
        }
        for (i, &c) in coverage.iter().enumerate() {
            if c > 0.0 {
                let x = bx0 + (i % bw) as i32;
                let y = by0 + (i / bw) as i32;
                blend(
                    &mut self.pixels,
                    self.width,
                    self.height,
                    x as f32,
                    y as f32,
                    color,
                    c * alpha,
                );
            }
        }
    }
}

/// Maximal runs of finite vertices of a polyline.
fn runs(line: &[(f64, f64)]) -> Vec<Vec<(f64, f64)>> {
    line.split(|p| !finite_pos(p.0, p.1))
        .filter(|r| !r.is_empty())
        .map(<[(f64, f64)]>::to_vec)
        .collect()
}

/// One entry of the legend.
#[derive(Debug, Clone, PartialEq)]
enum Entry {
    /// An outline: its label and colour index.
    Outline(String, usize),
    /// The grey used for particles without a finite value.
    Missing,
}

impl Entry {
    fn label(&self) -> &str {
        match self {
            Entry::Outline(text, _) => text,
            Entry::Missing => "no value (NaN)",
        }
    }
}

/// Legend entries (labelled drawable outlines, then the grey swatch if any particle has no
/// finite value) wrapped into rows of at most `MAP_MIN_WIDTH - 40` pixels.
fn legend_rows(spec: &ParticleMapSpec, painter: &TextPainter) -> Vec<Vec<(Entry, i32)>> {
    let mut entries: Vec<Entry> = spec
        .outlines
        .iter()
        .enumerate()
        .filter(|(_, (label, line))| !label.is_empty() && !runs(line).is_empty())
        .map(|(i, (label, _))| Entry::Outline(label.clone(), i))
        .collect();
    if spec
        .points
        .iter()
        .any(|p| finite_pos(p.x, p.y) && !p.value.is_finite())
    {
        entries.push(Entry::Missing);
    }
    let max_w = MAP_MIN_WIDTH as i32 - 40;
    let mut rows: Vec<Vec<(Entry, i32)>> = Vec::new();
    let mut row_w = 0;
    for e in entries {
        let w =
            LEGEND_SAMPLE_PX + 8 + painter.width(e.label(), LEGEND_FONT_PX as f32).ceil() as i32;
        match rows.last_mut() {
            Some(row) if row_w + LEGEND_ITEM_GAP + w <= max_w => {
                row_w += LEGEND_ITEM_GAP + w;
                row.push((e, w));
            }
            _ => {
                row_w = w;
                rows.push(vec![(e, w)]);
            }
        }
    }
    rows
}

fn render(spec: &ParticleMapSpec, lay: &Layout, painter: &TextPainter) -> Canvas {
    let mut c = Canvas::new(lay.width, lay.height);
    let plot = lay.plot_clip();

    // Particles: pixel-aligned squares, edges rounded so that markers one size apart touch;
    // a small tolerance keeps rounding noise in the positions from opening one-pixel gaps.
    let size = marker_size(spec);
    let m = if size > 0.0 {
        (size * lay.scale).max(1.0)
    } else {
        DEFAULT_MARKER_PX
    };
    let tol = if m > 1.0 { 0.05 } else { 0.0 };
    for p in spec.points.iter().filter(|p| finite_pos(p.x, p.y)) {
        let (px, py) = lay.to_px(p.x, p.y);
        let span = |centre: f64| {
            let lo = (centre - 0.5 * m - tol).round();
            let hi = (centre + 0.5 * m + tol).round().max(lo + 1.0);
            (lo as i32, hi as i32)
        };
        let (x0, x1) = span(px);
        let (y0, y1) = span(py);
        let cell = Clip {
            x0: x0.max(plot.x0),
            y0: y0.max(plot.y0),
            x1: x1.min(plot.x1),
            y1: y1.min(plot.y1),
        };
        c.fill(cell, viridis(colour_fraction(lay.colour, p.value)));
    }

    // Outlines on top, each over a white halo so it reads on dark and light colours alike.
    for (i, (_, line)) in spec.outlines.iter().enumerate() {
        let color = OUTLINE_COLORS[i % OUTLINE_COLORS.len()];
        let pixel_runs: Vec<Vec<(f64, f64)>> = runs(line)
            .into_iter()
            .map(|r| r.into_iter().map(|(x, y)| lay.to_px(x, y)).collect())
            .collect();
        for run in &pixel_runs {
            c.stroke(
                run,
                HALO_HALF_WIDTH,
                RGBColor(255, 255, 255),
                HALO_ALPHA,
                plot,
            );
        }
        for run in &pixel_runs {
            c.stroke(run, OUTLINE_HALF_WIDTH, color, 1.0, plot);
        }
    }

    let mut jobs = Vec::new();
    draw_axes(&mut c, lay, spec, &mut jobs);
    draw_colour_bar(&mut c, lay, spec, &mut jobs);
    draw_legend(&mut c, lay, &mut jobs);
    for job in &jobs {
        painter.draw(&mut c.pixels, c.width, c.height, job, TEXT_COLOR);
    }
    c
}

/// Frame, outward tick marks, tick labels, axis names and title.
fn draw_axes(c: &mut Canvas, lay: &Layout, spec: &ParticleMapSpec, jobs: &mut Vec<TextJob>) {
    let (left, top, right, bottom) = (lay.left, lay.top, lay.left + lay.pw, lay.top + lay.ph);
    c.border(
        Clip {
            x0: left - 1,
            y0: top - 1,
            x1: right + 1,
            y1: bottom + 1,
        },
        FRAME_COLOR,
    );
    let tick_px = TICK_FONT_PX as f32;
    for (v, text) in &lay.x_ticks {
        let col = (lay.to_px(*v, 0.0).0.floor() as i32).clamp(left, right - 1);
        c.fill(
            Clip {
                x0: col,
                y0: bottom + 1,
                x1: col + 1,
                y1: bottom + 1 + TICK_LEN,
            },
            FRAME_COLOR,
        );
        jobs.push(TextJob {
            text: text.clone(),
            px: tick_px,
            x: col as f32 + 0.5,
            y: (bottom + 1 + TICK_LEN + TICK_GAP) as f32,
            h: HAlign::Center,
            v: VAlign::Top,
            vertical: false,
        });
    }
    for (v, text) in &lay.y_ticks {
        let row = (lay.to_px(0.0, *v).1.floor() as i32).clamp(top, bottom - 1);
        c.fill(
            Clip {
                x0: left - 1 - TICK_LEN,
                y0: row,
                x1: left - 1,
                y1: row + 1,
            },
            FRAME_COLOR,
        );
        jobs.push(TextJob {
            text: text.clone(),
            px: tick_px,
            x: (left - 1 - TICK_LEN - TICK_GAP) as f32,
            y: row as f32 + 0.5,
            h: HAlign::Right,
            v: VAlign::Center,
            vertical: false,
        });
    }

    let centre_x = 0.5 * (left + right) as f32;
    let centre_y = 0.5 * (top + bottom) as f32;
    if !spec.title.is_empty() {
        jobs.push(TextJob {
            text: spec.title.clone(),
            px: TITLE_FONT_PX as f32,
            x: centre_x,
            y: 0.5 * lay.legend_top as f32,
            h: HAlign::Center,
            v: VAlign::Center,
            vertical: false,
        });
    }
    jobs.push(TextJob {
        text: spec.x_label.clone(),
        px: AXIS_DESC_FONT_PX as f32,
        x: centre_x,
        y: (bottom + 1 + TICK_LEN + TICK_GAP + TICK_FONT_PX as i32 + 14) as f32,
        h: HAlign::Center,
        v: VAlign::Top,
        vertical: false,
    });
    jobs.push(TextJob {
        text: spec.y_label.clone(),
        px: AXIS_DESC_FONT_PX as f32,
        x: (14.0 + 0.5 * AXIS_DESC_FONT_PX) as f32,
        y: centre_y,
        h: HAlign::Center,
        v: VAlign::Center,
        vertical: true,
    });
}

/// Vertical viridis bar beside the plot, framed, with min / mid / max labels and its name.
fn draw_colour_bar(c: &mut Canvas, lay: &Layout, spec: &ParticleMapSpec, jobs: &mut Vec<TextJob>) {
    let (x0, x1) = (lay.cb_left, lay.cb_left + CB_WIDTH);
    let (top, bottom) = (lay.top, lay.top + lay.ph);
    let rows = (lay.ph - 1).max(1);
    for row in top..bottom {
        let t = f64::from(bottom - 1 - row) / f64::from(rows);
        c.fill(
            Clip {
                x0,
                y0: row,
                x1,
                y1: row + 1,
            },
            viridis(t),
        );
    }
    c.border(
        Clip {
            x0: x0 - 1,
            y0: top - 1,
            x1: x1 + 1,
            y1: bottom + 1,
        },
        FRAME_COLOR,
    );
    let label_x = x1 + 1 + TICK_LEN + TICK_GAP;
    for (t, text) in &lay.cb_ticks {
        let row = bottom - 1 - (t * f64::from(rows)).round() as i32;
        c.fill(
            Clip {
                x0: x1 + 1,
                y0: row,
                x1: x1 + 1 + TICK_LEN,
                y1: row + 1,
            },
            FRAME_COLOR,
        );
        jobs.push(TextJob {
            text: text.clone(),
            px: TICK_FONT_PX as f32,
            x: label_x as f32,
            y: row as f32 + 0.5,
            h: HAlign::Left,
            v: VAlign::Center,
            vertical: false,
        });
    }
    if !spec.value_label.is_empty() {
        jobs.push(TextJob {
            text: spec.value_label.clone(),
            px: AXIS_DESC_FONT_PX as f32,
            x: label_x as f32 + lay.cb_label_w.ceil() + 14.0 + 0.5 * AXIS_DESC_FONT_PX as f32,
            y: 0.5 * (top + bottom) as f32,
            h: HAlign::Center,
            v: VAlign::Center,
            vertical: true,
        });
    }
}

/// Legend above the plot: one row per `lay.legend_rows` entry row, each row centred on the
/// plotting area (kept inside the image); line samples for outlines, a grey square for
/// particles without a value.
fn draw_legend(c: &mut Canvas, lay: &Layout, jobs: &mut Vec<TextJob>) {
    let centre = lay.left + lay.pw / 2;
    for (r, row) in lay.legend_rows.iter().enumerate() {
        let row_w: i32 =
            row.iter().map(|(_, w)| w).sum::<i32>() + LEGEND_ITEM_GAP * (row.len() as i32 - 1);
        let mut x = (centre - row_w / 2).clamp(10, (lay.width as i32 - 10 - row_w).max(10));
        let cy = lay.legend_top + LEGEND_ROW_H * r as i32 + LEGEND_ROW_H / 2;
        for (entry, w) in row {
            let x1 = x + LEGEND_SAMPLE_PX;
            match entry {
                Entry::Outline(_, i) => {
                    let color = OUTLINE_COLORS[i % OUTLINE_COLORS.len()];
                    let y = f64::from(cy) + 0.5;
                    let whole = Clip {
                        x0: 0,
                        y0: 0,
                        x1: lay.width as i32,
                        y1: lay.height as i32,
                    };
                    c.stroke(
                        &[(f64::from(x) + 1.0, y), (f64::from(x1) - 1.0, y)],
                        OUTLINE_HALF_WIDTH,
                        color,
                        1.0,
                        whole,
                    );
                }
                Entry::Missing => {
                    let s = 12;
                    let sx = (x + x1) / 2 - s / 2;
                    let square = Clip {
                        x0: sx,
                        y0: cy - s / 2,
                        x1: sx + s,
                        y1: cy - s / 2 + s,
                    };
                    c.fill(square, NAN_COLOR);
                    c.border(square, [128, 128, 128]);
                }
            }
            jobs.push(TextJob {
                text: entry.label().to_string(),
                px: LEGEND_FONT_PX as f32,
                x: (x1 + 8) as f32,
                y: cy as f32 + 0.5,
                h: HAlign::Left,
                v: VAlign::Center,
                vertical: false,
            });
            x += w + LEGEND_ITEM_GAP;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Decoded RGB image.
    struct Image {
        width: u32,
        height: u32,
        rgb: Vec<u8>,
    }

    impl Image {
        fn at(&self, x: i64, y: i64) -> [u8; 3] {
            assert!(x >= 0 && y >= 0 && x < i64::from(self.width) && y < i64::from(self.height));
            let i = 3 * (y as usize * self.width as usize + x as usize);
            [self.rgb[i], self.rgb[i + 1], self.rgb[i + 2]]
        }
    }

    fn decode(path: &Path) -> Image {
        let bytes = std::fs::read(path).expect("read png");
        assert_eq!(bytes[..8], [0x89, b'P', b'N', b'G', 0x0D, 0x0A, 0x1A, 0x0A]);
        let mut reader = png::Decoder::new(bytes.as_slice())
            .read_info()
            .expect("png header");
        let mut rgb = vec![0; reader.output_buffer_size()];
        let info = reader.next_frame(&mut rgb).expect("png data");
        assert_eq!(info.color_type, png::ColorType::Rgb);
        assert_eq!(info.bit_depth, png::BitDepth::Eight);
        rgb.truncate(info.buffer_size());
        Image {
            width: info.width,
            height: info.height,
            rgb,
        }
    }

    fn layout(spec: &ParticleMapSpec) -> Layout {
        Layout::new(spec, &TextPainter::new().unwrap()).unwrap()
    }

    fn close(a: [u8; 3], b: [u8; 3], tol: u8) -> bool {
        a.iter().zip(b).all(|(&p, q)| p.abs_diff(q) <= tol)
    }

    /// A `nx x ny` lattice of spacing `h` starting at the origin, valued by `f(x, y)`.
    fn lattice(nx: usize, ny: usize, h: f64, f: impl Fn(f64, f64) -> f64) -> Vec<MapPoint> {
        let mut out = Vec::with_capacity(nx * ny);
        for j in 0..ny {
            for i in 0..nx {
                let (x, y) = ((i as f64 + 0.5) * h, (j as f64 + 0.5) * h);
                out.push(MapPoint::new(x, y, f(x, y)));
            }
        }
        out
    }

    /// Synthetic effective plastic strain of a Taylor bar section (mm), peaking at the impact
    /// face y = 0 and on the axis.
    fn taylor_strain(x: f64, y: f64) -> f64 {
        2.1 * (-y / 2.6).exp() * (1.0 - 0.35 * (x / 3.2).powi(2)) + 0.08 * (-y / 14.0).exp()
    }

    /// Taylor-bar-like section: a 40 x 216 lattice of spacing 0.16 mm (radius 3.2 mm, height
    /// 34.56 mm) coloured by [`taylor_strain`], two particles without a value, and the
    /// analytic 0.5 contour of the field as an outline.
    fn taylor_spec() -> ParticleMapSpec {
        let (h, r0) = (0.16, 3.2);
        let mut points = Vec::new();
        for j in 0..216 {
            for i in 0..40 {
                let x = -r0 + (f64::from(i) + 0.5) * h;
                let y = (f64::from(j) + 0.5) * h;
                points.push(MapPoint::new(x, y, taylor_strain(x, y)));
            }
        }
        points[60 * 40 + 20].value = f64::NAN;
        points[150 * 40 + 7].value = f64::INFINITY;
        // The strain decreases with y: bisect for the height of the 0.5 contour at each x.
        let contour: Vec<(f64, f64)> = (0..=64)
            .map(|k| {
                let x = -r0 + 2.0 * r0 * f64::from(k) / 64.0;
                let (mut lo, mut hi) = (0.0, 34.56);
                for _ in 0..60 {
                    let mid = 0.5 * (lo + hi);
                    if taylor_strain(x, mid) > 0.5 {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                (x, 0.5 * (lo + hi))
            })
            .collect();
        ParticleMapSpec {
            title: "Taylor bar: effective plastic strain".into(),
            x_label: "radial position x [mm]".into(),
            y_label: "axial position y [mm]".into(),
            value_label: "effective plastic strain [-]".into(),
            range: None,
            marker_size: h,
            points,
            outlines: vec![("reference: 0.5 contour".into(), contour)],
        }
    }

    #[test]
    fn viridis_table() {
        assert_eq!(viridis(0.0), [68, 1, 84]);
        assert_eq!(viridis(128.0 / 255.0), [33, 145, 140]);
        assert_eq!(viridis(1.0), [253, 231, 37]);
        assert_eq!(viridis(-3.0), viridis(0.0));
        assert_eq!(viridis(7.0), viridis(1.0));
        assert_eq!(viridis(f64::NAN), NAN_COLOR);
        // Perceptually ordered: luma grows monotonically along the map.
        let luma = |c: [u8; 3]| {
            0.299 * f64::from(c[0]) + 0.587 * f64::from(c[1]) + 0.114 * f64::from(c[2])
        };
        for k in 0..100 {
            let (a, b) = (f64::from(k) / 100.0, f64::from(k + 1) / 100.0);
            assert!(luma(viridis(b)) >= luma(viridis(a)), "{a}");
        }
    }

    #[test]
    fn writes_valid_png() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("map.png");
        let spec = taylor_spec();
        write_particle_map(&path, &spec).unwrap();
        let img = decode(&path);
        let lay = layout(&spec);
        assert_eq!((img.width, img.height), (lay.width, lay.height));
        assert!(std::fs::metadata(&path).unwrap().len() > 5_000);
        let leftovers: Vec<_> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(leftovers, vec![std::ffi::OsString::from("map.png")]);
        if let Some(dir) = std::env::var_os("TLSPH_PLOT_SAMPLES") {
            std::fs::copy(&path, Path::new(&dir).join("particle_map_sample.png")).unwrap();
        }
    }

    #[test]
    fn output_is_deterministic() {
        let dir = tempfile::tempdir().unwrap();
        let (a, b) = (dir.path().join("a.png"), dir.path().join("b.png"));
        write_particle_map(&a, &taylor_spec()).unwrap();
        write_particle_map(&b, &taylor_spec()).unwrap();
        assert_eq!(std::fs::read(a).unwrap(), std::fs::read(b).unwrap());
    }

    /// Bounding box of the plotting-area pixels with exactly `color`: (x0, y0, x1, y1),
    /// inclusive.
    fn bbox_of(img: &Image, lay: &Layout, color: [u8; 3]) -> (i64, i64, i64, i64) {
        let mut b = (i64::MAX, i64::MAX, i64::MIN, i64::MIN);
        for y in i64::from(lay.top)..i64::from(lay.top + lay.ph) {
            for x in i64::from(lay.left)..i64::from(lay.left + lay.pw) {
                if img.at(x, y) == color {
                    b = (b.0.min(x), b.1.min(y), b.2.max(x), b.3.max(y));
                }
            }
        }
        b
    }

    #[test]
    fn aspect_ratio_is_equal() {
        let dir = tempfile::tempdir().unwrap();
        // A 1 x 4 domain (10 x 40 particles of size 0.1), constant value: one solid block.
        let tall = ParticleMapSpec {
            marker_size: 0.1,
            points: lattice(10, 40, 0.1, |_, _| 2.0),
            ..Default::default()
        };
        let path = dir.path().join("tall.png");
        write_particle_map(&path, &tall).unwrap();
        let img = decode(&path);
        assert!(img.height > img.width, "{}x{}", img.width, img.height);
        assert!(img.height <= MAP_MAX_HEIGHT && img.width >= MAP_MIN_WIDTH);
        // The constant field is the middle colour; its block is exactly 1:4.
        let (x0, y0, x1, y1) = bbox_of(&img, &layout(&tall), viridis(0.5));
        let (w, h) = ((x1 - x0 + 1) as f64, (y1 - y0 + 1) as f64);
        assert!((h / w - 4.0).abs() < 0.05, "block {w} x {h}");
        // Every particle is a solid square: no white gaps inside the block.
        for y in y0..=y1 {
            for x in x0..=x1 {
                assert_eq!(img.at(x, y), viridis(0.5), "gap at ({x}, {y})");
            }
        }

        // A 4 x 1 domain is wider than tall, and within the height limits.
        let wide = ParticleMapSpec {
            title: "Plate: von Mises stress".into(),
            x_label: "x [m]".into(),
            y_label: "y [m]".into(),
            value_label: "σ_vM [Pa]".into(),
            marker_size: 0.1,
            points: lattice(40, 10, 0.1, |x, y| 2.4e8 * x * (1.0 + y) / 8.0),
            outlines: vec![(String::new(), vec![(0.0, 0.0), (4.0, 1.0)])],
            ..Default::default()
        };
        let path = dir.path().join("wide.png");
        write_particle_map(&path, &wide).unwrap();
        if let Some(dir) = std::env::var_os("TLSPH_PLOT_SAMPLES") {
            std::fs::copy(&path, Path::new(&dir).join("particle_map_wide.png")).unwrap();
        }
        let img = decode(&path);
        assert_eq!(img.width, MAP_WIDTH);
        assert!(img.width > img.height && img.height >= MAP_MIN_HEIGHT);
        let lay = layout(&wide);
        let sx = f64::from(lay.pw) / (lay.x.hi - lay.x.lo);
        let sy = f64::from(lay.ph) / (lay.y.hi - lay.y.lo);
        assert!((sx / sy - 1.0).abs() < 1e-12, "{sx} vs {sy}");
    }

    #[test]
    fn colours_follow_values_and_nan_is_grey() {
        let dir = tempfile::tempdir().unwrap();
        let spec = ParticleMapSpec {
            title: "colours".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            value_label: "v".into(),
            range: None,
            marker_size: 1.0,
            points: vec![
                MapPoint::new(0.0, 0.0, -3.0),
                MapPoint::new(2.0, 0.0, 5.0),
                MapPoint::new(4.0, 0.0, f64::NAN),
                MapPoint::new(6.0, 0.0, 1.0),
                MapPoint::new(8.0, 0.0, f64::NEG_INFINITY),
            ],
            outlines: vec![],
        };
        let path = dir.path().join("colours.png");
        write_particle_map(&path, &spec).unwrap();
        let img = decode(&path);
        let lay = layout(&spec);
        let sample = |p: &MapPoint| {
            let (x, y) = lay.to_px(p.x, p.y);
            img.at(x.floor() as i64, y.floor() as i64)
        };
        let pts = &spec.points;
        assert!(
            close(sample(&pts[0]), viridis(0.0), 1),
            "{:?}",
            sample(&pts[0])
        );
        assert!(close(sample(&pts[0]), [68, 1, 84], 1));
        assert!(
            close(sample(&pts[1]), [253, 231, 37], 1),
            "{:?}",
            sample(&pts[1])
        );
        assert!(
            close(sample(&pts[3]), viridis(0.5), 1),
            "{:?}",
            sample(&pts[3])
        );
        for p in [&pts[2], &pts[4]] {
            let [r, g, b] = sample(p);
            assert!(
                r == g && g == b && (100..=200).contains(&r),
                "{:?}",
                [r, g, b]
            );
        }

        // An explicit range clamps: -3 and 1 both below 2, 5 above 4.
        let mut ranged = spec.clone();
        ranged.range = Some((2.0, 4.0));
        write_particle_map(&path, &ranged).unwrap();
        let img = decode(&path);
        let sample = |p: &MapPoint| {
            let (x, y) = lay.to_px(p.x, p.y);
            img.at(x.floor() as i64, y.floor() as i64)
        };
        assert_eq!(sample(&pts[0]), viridis(0.0));
        assert_eq!(sample(&pts[3]), viridis(0.0));
        assert_eq!(sample(&pts[1]), viridis(1.0));
    }

    #[test]
    fn no_data_is_an_error() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("sub").join("none.png");
        let mut spec = ParticleMapSpec {
            title: "empty".into(),
            marker_size: 1.0,
            outlines: vec![("shape".into(), vec![(0.0, 0.0), (1.0, 1.0)])],
            ..Default::default()
        };
        let err = write_particle_map(&path, &spec).unwrap_err();
        assert!(matches!(err, PlotError::NoData { .. }), "{err:?}");
        assert!(err.to_string().contains("none.png"), "{err}");
        spec.points = vec![
            MapPoint::new(f64::NAN, 0.0, 1.0),
            MapPoint::new(0.0, f64::INFINITY, 1.0),
        ];
        assert!(matches!(
            write_particle_map(&path, &spec),
            Err(PlotError::NoData { .. })
        ));
        assert!(!path.exists());
    }

    #[test]
    fn io_error_names_the_path() {
        let dir = tempfile::tempdir().unwrap();
        let blocker = dir.path().join("not_a_dir");
        std::fs::write(&blocker, b"x").unwrap();
        let spec = ParticleMapSpec {
            points: vec![MapPoint::new(0.0, 0.0, 1.0)],
            ..Default::default()
        };
        let err = write_particle_map(&blocker.join("map.png"), &spec).unwrap_err();
        assert!(matches!(err, PlotError::Io { .. }), "{err:?}");
        assert!(err.to_string().contains("not_a_dir"), "{err}");
    }

    #[test]
    fn degenerate_inputs_still_draw() {
        let dir = tempfile::tempdir().unwrap();
        let cases: Vec<(&str, ParticleMapSpec)> = vec![
            (
                "single",
                ParticleMapSpec {
                    points: vec![MapPoint::new(3.0, -2.0, 0.5)],
                    ..Default::default()
                },
            ),
            (
                "origin_all_nan",
                ParticleMapSpec {
                    points: vec![MapPoint::new(0.0, 0.0, f64::NAN); 3],
                    marker_size: f64::NAN,
                    ..Default::default()
                },
            ),
            (
                "column",
                ParticleMapSpec {
                    points: (0..50)
                        .map(|j| MapPoint::new(1.0, f64::from(j), 0.0))
                        .collect(),
                    marker_size: -1.0,
                    range: Some((1.0, 1.0)),
                    ..Default::default()
                },
            ),
            (
                "row_reversed_range",
                ParticleMapSpec {
                    points: (0..500)
                        .map(|i| MapPoint::new(f64::from(i) * 1e-4, 7.0, f64::from(i)))
                        .collect(),
                    marker_size: 1e-4,
                    range: Some((500.0, 0.0)),
                    ..Default::default()
                },
            ),
            (
                "huge_values",
                ParticleMapSpec {
                    points: lattice(5, 5, 1e3, |x, y| 1e9 * (x - y)),
                    marker_size: 1e3,
                    range: Some((f64::NAN, 3.0)),
                    ..Default::default()
                },
            ),
        ];
        for (name, spec) in cases {
            let path = dir.path().join(format!("{name}.png"));
            write_particle_map(&path, &spec).unwrap();
            let img = decode(&path);
            assert!(
                (MAP_MIN_HEIGHT..=MAP_MAX_HEIGHT).contains(&img.height),
                "{name}"
            );
            assert!((MAP_MIN_WIDTH..=MAP_WIDTH).contains(&img.width), "{name}");
        }
    }

    #[test]
    fn colour_bar_labels() {
        assert_eq!(value_text((0.0, 0.8734), 0.8734), "0.873");
        assert_eq!(value_text((0.0, 0.8734), 0.4367), "0.437");
        assert_eq!(value_text((0.0, 0.8734), 0.0), "0");
        assert_eq!(value_text((0.0, 2.5e8), 1.25e8), "1.25e8");
        assert_eq!(value_text((-40.0, 40.0), -40.0), "-40");
        assert_eq!(colour_range(&ParticleMapSpec::default()), (0.0, 1.0));
    }
}
