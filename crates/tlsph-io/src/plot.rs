//! PNG line plots for the validation harness: simulation vs reference curves, log-log error plots.
//!
//! Lines, markers, grid and legend box are drawn with `plotters` (bitmap backend) into an
//! in-memory RGB buffer; all text is laid out and anti-aliased here with `ab_glyph` (plotters'
//! own `ab_glyph` text path drops glyph side bearings and spaces letters unevenly). The font,
//! DejaVu Sans (Bitstream Vera licence, see `assets/LICENSE-DejaVu.txt`), is embedded with
//! `include_bytes!`, so no system font library (fontconfig, freetype) is needed. The buffer is
//! encoded with the `png` crate into a temporary file in the target directory, which is then
//! renamed over the target, so a reader never sees a half-written file.
//!
//! Coloured particle maps (a scalar field over particle positions, with a colour bar) are in
//! [`crate::particle_map`] and re-exported here; they share this module's text rendering, tick
//! labels, [`PlotError`] and atomic writing.
//!
//! Setting `TLSPH_PLOT_SAMPLES=<dir>` while running this module's tests also copies two sample
//! figures (`plot_sample.png`, `plot_loglog.png`) into `<dir>` for a visual check.

use std::fmt;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use ab_glyph::{point, Font, FontRef, PxScale, ScaleFont};
use plotters::coord::ranged1d::{BoldPoints, ValueFormatter};
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

pub use crate::particle_map::{viridis, write_particle_map, MapPoint, ParticleMapSpec};

/// Width of every written PNG, in pixels.
pub const PLOT_WIDTH: u32 = 900;
/// Height of every written PNG, in pixels.
pub const PLOT_HEIGHT: u32 = 600;

/// Family name under which the embedded font is registered; plotters' default text styles use it.
const FONT_FAMILY: &str = "sans-serif";
/// DejaVu Sans 2.37 (see `assets/LICENSE-DejaVu.txt`).
static FONT_TTF: &[u8] = include_bytes!("../assets/DejaVuSans.ttf");

/// Series colours (the "tab10" palette), cycled when there are more series.
const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

/// Colour of all text.
pub(crate) const TEXT_COLOR: RGBColor = RGBColor(20, 20, 20);
/// Maximum number of labelled (bold) ticks per axis.
pub(crate) const N_TICK_LABELS: usize = 10;
pub(crate) const TITLE_FONT_PX: f64 = 22.0;
pub(crate) const AXIS_DESC_FONT_PX: f64 = 17.0;
pub(crate) const TICK_FONT_PX: f64 = 14.0;
pub(crate) const LEGEND_FONT_PX: f64 = 15.0;
const LINE_WIDTH: u32 = 2;
const MARKER_RADIUS: i32 = 4;
const DASH_PX: i32 = 10;
const DASH_GAP_PX: i32 = 6;
/// Horizontal extent of the line sample drawn in front of each legend label.
pub(crate) const LEGEND_SAMPLE_PX: i32 = 26;

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SeriesStyle {
    /// Solid polyline through the points.
    Line,
    /// Dashed polyline through the points (typically reference curves).
    DashedLine,
    /// A filled circle at every point, no connecting line.
    Markers,
    /// Solid polyline with a filled circle at every point.
    LineWithMarkers,
}

/// One data series.
#[derive(Debug, Clone, PartialEq)]
pub struct PlotSeries {
    /// Legend text; an empty label gives the series no legend entry.
    pub label: String,
    /// `(x, y)` points in drawing order. Non-finite points (and points `<= 0` on a log axis)
    /// are skipped and break the line there.
    pub points: Vec<(f64, f64)>,
    /// How the series is drawn.
    pub style: SeriesStyle,
}

impl PlotSeries {
    /// Convenience constructor.
    pub fn new(label: impl Into<String>, points: Vec<(f64, f64)>, style: SeriesStyle) -> Self {
        Self {
            label: label.into(),
            points,
            style,
        }
    }
}

/// A whole figure.
#[derive(Debug, Clone, PartialEq)]
pub struct PlotSpec {
    /// Caption above the plot (may be empty).
    pub title: String,
    /// Text under the x axis.
    pub x_label: String,
    /// Text beside the y axis.
    pub y_label: String,
    /// Logarithmic (base 10) x axis.
    pub log_x: bool,
    /// Logarithmic (base 10) y axis.
    pub log_y: bool,
    /// Series drawn in order; series `i` gets palette colour `i % 10`.
    pub series: Vec<PlotSeries>,
}

impl PlotSpec {
    /// A figure with linear axes and no series yet.
    pub fn new(
        title: impl Into<String>,
        x_label: impl Into<String>,
        y_label: impl Into<String>,
    ) -> Self {
        Self {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            log_x: false,
            log_y: false,
            series: Vec::new(),
        }
    }
}

/// Why a plot could not be written.
#[derive(Debug)]
pub enum PlotError {
    /// Creating the directory, writing the temporary file or renaming it failed.
    Io {
        /// The path that was being created or written.
        path: PathBuf,
        /// The underlying error.
        source: std::io::Error,
    },
    /// No series has a drawable point (all empty, non-finite, or `<= 0` on a log axis), or a
    /// particle map has no particle with a finite position.
    NoData {
        /// The plot that was asked for (nothing is written there).
        path: PathBuf,
    },
    /// Rendering or PNG encoding failed; the message names the output path.
    Backend(String),
}

impl fmt::Display for PlotError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PlotError::Io { path, source } => {
                write!(f, "cannot write plot {}: {source}", path.display())
            }
            PlotError::NoData { path } => write!(
                f,
                "cannot plot {}: no drawable data point (every series or particle set is \
                 empty, non-finite, or non-positive on a log axis)",
                path.display()
            ),
            PlotError::Backend(msg) => write!(f, "plot rendering failed: {msg}"),
        }
    }
}

impl std::error::Error for PlotError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            PlotError::Io { source, .. } => Some(source),
            _ => None,
        }
    }
}

/// Registers the embedded font with plotters exactly once (thread-safe).
fn ensure_font() -> Result<(), String> {
    static REGISTERED: OnceLock<Result<(), String>> = OnceLock::new();
    REGISTERED
        .get_or_init(|| {
            plotters::style::register_font(FONT_FAMILY, FontStyle::Normal, FONT_TTF)
                .map_err(|_| "the embedded DejaVu Sans font could not be parsed".to_string())
        })
        .clone()
}

/// Writes a PNG (`PLOT_WIDTH` x `PLOT_HEIGHT`) to `path`: written to a temporary file in the
/// same directory first, then renamed, so an existing file is never left half-written.
/// Creates the parent directory if missing.
pub fn write_png(path: &Path, spec: &PlotSpec) -> Result<(), PlotError> {
    let prepared = prepare(spec);
    if prepared.is_empty() {
        return Err(PlotError::NoData {
            path: path.to_path_buf(),
        });
    }
    let backend_err = |msg: String| PlotError::Backend(format!("{}: {msg}", path.display()));
    ensure_font().map_err(backend_err)?;
    let pixels = render(spec, &prepared).map_err(backend_err)?;
    write_atomically(path, &pixels, PLOT_WIDTH, PLOT_HEIGHT)
}

/// The drawable part of one input series.
struct Prepared<'a> {
    /// Index in `PlotSpec::series` (selects the colour).
    index: usize,
    series: &'a PlotSeries,
    /// Maximal runs of consecutive drawable points; lines are broken between runs.
    runs: Vec<Vec<(f64, f64)>>,
}

fn drawable(p: (f64, f64), log_x: bool, log_y: bool) -> bool {
    p.0.is_finite() && p.1.is_finite() && (!log_x || p.0 > 0.0) && (!log_y || p.1 > 0.0)
}

fn prepare(spec: &PlotSpec) -> Vec<Prepared<'_>> {
    let mut out = Vec::new();
    for (index, series) in spec.series.iter().enumerate() {
        let mut runs: Vec<Vec<(f64, f64)>> = Vec::new();
        let mut current = Vec::new();
        for &p in &series.points {
            if drawable(p, spec.log_x, spec.log_y) {
                current.push(p);
            } else if !current.is_empty() {
                runs.push(std::mem::take(&mut current));
            }
        }
        if !current.is_empty() {
            runs.push(current);
        }
        if !runs.is_empty() {
            out.push(Prepared {
                index,
                series,
                runs,
            });
        }
    }
    out
}

/// A finished axis range, `lo < hi`, both finite (and positive for log axes).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Axis {
    pub(crate) lo: f64,
    pub(crate) hi: f64,
    pub(crate) log: bool,
}

impl Axis {
    /// Range covering `[min, max]` with a small margin; degenerate ranges are widened.
    fn fit(min: f64, max: f64, log: bool) -> Self {
        let (lo, hi) = if log {
            log_range(min, max)
        } else {
            linear_range(min, max)
        };
        Axis { lo, hi, log }
    }

    /// Position of `v` along the axis, 0 at `lo` and 1 at `hi`.
    fn unit(&self, v: f64) -> f64 {
        if self.log {
            (v.log10() - self.lo.log10()) / (self.hi.log10() - self.lo.log10())
        } else {
            (v - self.lo) / (self.hi - self.lo)
        }
    }
}

fn linear_range(min: f64, max: f64) -> (f64, f64) {
    let scale = min.abs().max(max.abs());
    // Half-differences cannot overflow even for values near f64::MAX.
    let half_span = 0.5 * max - 0.5 * min;
    let (lo, hi) = if half_span > 0.5e-12 * scale {
        let margin = 0.1 * half_span;
        (min - margin, max + margin)
    } else {
        let d = if scale > 0.0 { 0.1 * scale } else { 1.0 };
        (min - d, max + d)
    };
    let lo = lo.max(-f64::MAX);
    let hi = hi.min(f64::MAX);
    if lo < hi {
        (lo, hi)
    } else {
        (min - 1.0, max + 1.0)
    }
}

/// `m * 10^k`, parsed from decimal text so powers of ten are exact to the last bit.
fn decimal(m: u32, k: i32) -> f64 {
    format!("{m}e{k}").parse().unwrap_or(f64::NAN)
}

/// Decade exponent `k` with `10^k <= v < 10^(k+1)` (for finite `v > 0`), clamped to f64 range.
fn decade(v: f64) -> i32 {
    let mut k = v.log10().floor().clamp(-300.0, 300.0) as i32;
    if decimal(1, k) > v {
        k -= 1;
    }
    if decimal(1, k + 1) <= v {
        k += 1;
    }
    k.clamp(-300, 300)
}

/// Largest `m * 10^k <= v` with `m` in {1, 2, 5}.
fn nice_floor(v: f64) -> (u32, i32) {
    let k = decade(v);
    let m = [5, 2, 1]
        .into_iter()
        .find(|&m| decimal(m, k) <= v)
        .unwrap_or(1);
    (m, k)
}

/// Smallest `m * 10^k >= v` with `m` in {1, 2, 5}.
fn nice_ceil(v: f64) -> (u32, i32) {
    let k = decade(v);
    match [1, 2, 5].into_iter().find(|&m| decimal(m, k) >= v) {
        Some(m) => (m, k),
        None => (1, k + 1),
    }
}

/// Log range: 5 % margin in log space, ends rounded out to 1-2-5 values, and widened to whole
/// decades when fewer than two powers of ten would fall inside (so the axis always gets labels).
fn log_range(min: f64, max: f64) -> (f64, f64) {
    let (a, b) = (min.log10(), max.log10());
    let (lo_e, hi_e) = if b - a < 1e-9 {
        (a - 0.5, b + 0.5)
    } else {
        let pad = 0.05 * (b - a);
        (a - pad, b + pad)
    };
    let (mut lo_m, mut lo_k) = nice_floor(10f64.powf(lo_e.clamp(-300.0, 300.0)));
    let (mut hi_m, mut hi_k) = nice_ceil(10f64.powf(hi_e.clamp(-300.0, 300.0)));
    let first_power = if lo_m == 1 { lo_k } else { lo_k + 1 };
    let last_power = hi_k;
    if last_power - first_power < 1 {
        lo_m = 1;
        if hi_m != 1 {
            hi_m = 1;
            hi_k += 1;
        }
        if hi_k <= lo_k {
            hi_k = lo_k + 1;
        }
    }
    lo_k = lo_k.clamp(-300, 300);
    hi_k = hi_k.clamp(-300, 301);
    // Nudge the ends outwards by a hair so that plotters' floating-point tick search
    // (logarithms and repeated multiplication) still finds the end values as ticks.
    (
        decimal(lo_m, lo_k) * (1.0 - 1e-9),
        decimal(hi_m, hi_k) * (1.0 + 1e-9),
    )
}

/// Removes trailing zeros after a decimal point (in the mantissa when in `e` notation).
pub(crate) fn trim_number(s: &str) -> String {
    let (mant, exp) = match s.split_once('e') {
        Some((m, e)) => (m, Some(e)),
        None => (s, None),
    };
    let mant = if mant.contains('.') {
        mant.trim_end_matches('0').trim_end_matches('.')
    } else {
        mant
    };
    let mant = if mant == "-0" { "0" } else { mant };
    match exp {
        Some(e) => format!("{mant}e{e}"),
        None => mant.to_string(),
    }
}

/// Tick label text for `v` on `axis`: plain decimals, or `1.5e-4` style for very large/small
/// magnitudes; digits follow the axis span so neighbouring labels differ.
pub(crate) fn tick_label(axis: &Axis, v: f64) -> String {
    if axis.log {
        let sci = axis.lo < 1e-3 || axis.hi > 1e4;
        if sci {
            trim_number(&format!("{v:.2e}"))
        } else {
            let decimals = (2 - decade(v)).clamp(0, 6) as usize;
            trim_number(&format!("{v:.decimals$}"))
        }
    } else {
        let span = axis.hi - axis.lo;
        if v.abs() <= 1e-9 * span {
            return "0".to_string();
        }
        let step_exp = (span / 25.0).log10().floor() as i32;
        let max_abs = axis.lo.abs().max(axis.hi.abs());
        if !(1e-3..1e5).contains(&max_abs) {
            let digits = (v.abs().log10().floor() as i32 - step_exp).clamp(0, 12) as usize;
            trim_number(&format!("{v:.digits$e}"))
        } else {
            let decimals = (-step_exp).clamp(0, 12) as usize;
            trim_number(&format!("{v:.decimals$}"))
        }
    }
}

/// A corner of the plotting area.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Corner {
    right: bool,
    top: bool,
}

/// Picks the plot corner whose neighbourhood (a box of `legend_w x legend_h`, as fractions of
/// the plotting area) holds the fewest data points, counting points sampled along line
/// segments too, so the legend hides as little data as possible. Ties prefer upper right.
fn legend_corner(
    prepared: &[Prepared<'_>],
    x: &Axis,
    y: &Axis,
    legend_w: f64,
    legend_h: f64,
) -> Corner {
    let corners = [
        Corner {
            right: true,
            top: true,
        },
        Corner {
            right: false,
            top: true,
        },
        Corner {
            right: true,
            top: false,
        },
        Corner {
            right: false,
            top: false,
        },
    ];
    let mut counts = [0usize; 4];
    let mut count_point = |u: f64, v: f64| {
        for (c, corner) in corners.iter().enumerate() {
            let in_x = if corner.right {
                u >= 1.0 - legend_w
            } else {
                u <= legend_w
            };
            let in_y = if corner.top {
                v >= 1.0 - legend_h
            } else {
                v <= legend_h
            };
            if in_x && in_y {
                counts[c] += 1;
            }
        }
    };
    for p in prepared {
        let lines = p.series.style != SeriesStyle::Markers;
        for run in &p.runs {
            let mut prev: Option<(f64, f64)> = None;
            for &(px, py) in run {
                let (u, v) = (x.unit(px), y.unit(py));
                count_point(u, v);
                if let (true, Some((pu, pv))) = (lines, prev) {
                    for s in 1..8 {
                        let t = f64::from(s) / 8.0;
                        count_point(pu + t * (u - pu), pv + t * (v - pv));
                    }
                }
                prev = Some((u, v));
            }
        }
    }
    let best = (0..corners.len()).min_by_key(|&c| counts[c]).unwrap_or(0);
    corners[best]
}

/// Horizontal anchor of a text job (along the reading direction).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum HAlign {
    Left,
    Center,
    Right,
}

/// Vertical anchor of a text job (across the reading direction).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum VAlign {
    Top,
    Center,
}

/// A piece of text to draw once plotters has finished with the pixel buffer.
#[derive(Debug, Clone)]
pub(crate) struct TextJob {
    pub(crate) text: String,
    pub(crate) px: f32,
    pub(crate) x: f32,
    pub(crate) y: f32,
    pub(crate) h: HAlign,
    pub(crate) v: VAlign,
    /// Rotated 90 degrees counter-clockwise (reads bottom to top).
    pub(crate) vertical: bool,
}

/// Text measurement and anti-aliased rasterisation with the embedded font.
///
/// Plotters' own `ab_glyph` text path drops each glyph's left side bearing, which gives uneven
/// letter spacing; all visible text is therefore laid out here (with kerning and sub-pixel
/// positions) and blended into the RGB buffer after plotters has drawn lines and the mesh.
pub(crate) struct TextPainter {
    font: FontRef<'static>,
}

impl TextPainter {
    pub(crate) fn new() -> Result<Self, String> {
        FontRef::try_from_slice(FONT_TTF)
            .map(|font| Self { font })
            .map_err(|e| format!("embedded font: {e}"))
    }

    /// Advance width of `text` at pixel height `px`, including kerning.
    pub(crate) fn width(&self, text: &str, px: f32) -> f32 {
        let font = self.font.as_scaled(PxScale::from(px));
        let mut w = 0.0;
        let mut prev = None;
        for c in text.chars() {
            let id = font.glyph_id(c);
            if let Some(p) = prev {
                w += font.kern(p, id);
            }
            w += font.h_advance(id);
            prev = Some(id);
        }
        w
    }

    /// Blends the text into a tightly packed RGB buffer of `width x height` pixels.
    pub(crate) fn draw(
        &self,
        pixels: &mut [u8],
        width: u32,
        height: u32,
        job: &TextJob,
        color: RGBColor,
    ) {
        let scale = PxScale::from(job.px);
        let font = self.font.as_scaled(scale);
        let w = self.width(&job.text, job.px);
        // Text-frame origin: pen starts at x = 0, baseline at y = 0, y grows downwards.
        let start = match job.h {
            HAlign::Left => 0.0,
            HAlign::Center => -0.5 * w,
            HAlign::Right => -w,
        };
        let baseline = match job.v {
            VAlign::Top => font.ascent(),
            VAlign::Center => 0.5 * (font.ascent() + font.descent()),
        };
        // For rotated text the origin is snapped to whole pixels; glyphs keep sub-pixel offsets.
        let (ox, oy) = if job.vertical {
            (job.x.round(), job.y.round())
        } else {
            (job.x, job.y)
        };
        let mut pen = start;
        let mut prev = None;
        for c in job.text.chars() {
            let id = font.glyph_id(c);
            if let Some(p) = prev {
                pen += font.kern(p, id);
            }
            prev = Some(id);
            let pos = if job.vertical {
                point(pen, baseline)
            } else {
                point(ox + pen, oy + baseline)
            };
            pen += font.h_advance(id);
            let Some(outline) = self
                .font
                .outline_glyph(id.with_scale_and_position(scale, pos))
            else {
                continue;
            };
            let bounds = outline.px_bounds();
            outline.draw(|gx, gy, coverage| {
                let fx = bounds.min.x + gx as f32;
                let fy = bounds.min.y + gy as f32;
                let (sx, sy) = if job.vertical {
                    (ox + fy, oy - fx)
                } else {
                    (fx, fy)
                };
                blend(pixels, width, height, sx, sy, color, coverage);
            });
        }
    }
}

/// Alpha-blends `color` with weight `alpha` into the pixel at (`x`, `y`) if it is inside.
pub(crate) fn blend(
    pixels: &mut [u8],
    width: u32,
    height: u32,
    x: f32,
    y: f32,
    color: RGBColor,
    alpha: f32,
) {
    let (x, y) = (x.round(), y.round());
    if x < 0.0 || y < 0.0 || x >= width as f32 || y >= height as f32 {
        return;
    }
    let a = alpha.clamp(0.0, 1.0);
    let i = 3 * (y as usize * width as usize + x as usize);
    for (k, c) in [color.0, color.1, color.2].into_iter().enumerate() {
        let old = f32::from(pixels[i + k]);
        pixels[i + k] = (old + (f32::from(c) - old) * a).round() as u8;
    }
}

/// Renders the figure into an RGB buffer of `PLOT_WIDTH * PLOT_HEIGHT * 3` bytes.
fn render(spec: &PlotSpec, prepared: &[Prepared<'_>]) -> Result<Vec<u8>, String> {
    let mut xmin = f64::INFINITY;
    let mut xmax = f64::NEG_INFINITY;
    let mut ymin = f64::INFINITY;
    let mut ymax = f64::NEG_INFINITY;
    for p in prepared {
        for &(px, py) in p.runs.iter().flatten() {
            xmin = xmin.min(px);
            xmax = xmax.max(px);
            ymin = ymin.min(py);
            ymax = ymax.max(py);
        }
    }
    let x = Axis::fit(xmin, xmax, spec.log_x);
    let y = Axis::fit(ymin, ymax, spec.log_y);

    let painter = TextPainter::new()?;
    let mut pixels = vec![255u8; (PLOT_WIDTH * PLOT_HEIGHT * 3) as usize];
    let lin = |a: &Axis| RangedCoordf64::from(a.lo..a.hi);
    let log = |a: &Axis| LogCoord::from((a.lo..a.hi).log_scale());
    let jobs = match (x.log, y.log) {
        (false, false) => draw_chart(
            &mut pixels,
            &painter,
            spec,
            prepared,
            &x,
            &y,
            lin(&x),
            lin(&y),
        ),
        (true, false) => draw_chart(
            &mut pixels,
            &painter,
            spec,
            prepared,
            &x,
            &y,
            log(&x),
            lin(&y),
        ),
        (false, true) => draw_chart(
            &mut pixels,
            &painter,
            spec,
            prepared,
            &x,
            &y,
            lin(&x),
            log(&y),
        ),
        (true, true) => draw_chart(
            &mut pixels,
            &painter,
            spec,
            prepared,
            &x,
            &y,
            log(&x),
            log(&y),
        ),
    }?;
    for job in &jobs {
        painter.draw(&mut pixels, PLOT_WIDTH, PLOT_HEIGHT, job, TEXT_COLOR);
    }
    Ok(pixels)
}

/// Draws frame, mesh, ticks, all series and the legend box with plotters, and returns the text
/// (title, axis labels, tick labels, legend labels) to be drawn afterwards by [`TextPainter`].
#[allow(clippy::too_many_arguments)]
fn draw_chart<XC, YC>(
    pixels: &mut [u8],
    painter: &TextPainter,
    spec: &PlotSpec,
    prepared: &[Prepared<'_>],
    x: &Axis,
    y: &Axis,
    x_coord: XC,
    y_coord: YC,
) -> Result<Vec<TextJob>, String>
where
    XC: Ranged<ValueType = f64> + ValueFormatter<f64>,
    YC: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let err = |e: DrawingAreaErrorKind<_>| e.to_string();
    let mut jobs = Vec::new();

    // Tick values are the key points plotters uses for its bold mesh lines (same hint).
    let tick_px = TICK_FONT_PX as f32;
    let ticks = |coord: &dyn Fn(usize) -> Vec<f64>, axis: &Axis, n: usize| -> Vec<(f64, String)> {
        coord(n)
            .into_iter()
            .map(|v| (v, tick_label(axis, v)))
            .collect()
    };
    let x_keys = |n: usize| x_coord.key_points(BoldPoints(n));
    let y_keys = |n: usize| y_coord.key_points(BoldPoints(n));
    let y_ticks = ticks(&y_keys, y, N_TICK_LABELS);
    let y_tick_w = y_ticks
        .iter()
        .map(|(_, t)| painter.width(t, tick_px))
        .fold(0.0f32, f32::max);

    // Layout (pixels): title band, left band (axis name + tick labels), bottom band.
    let top = if spec.title.is_empty() { 16 } else { 48 };
    let right_margin = 30;
    let tick_len = 5;
    let gap = 6;
    let left_band = 14 + AXIS_DESC_FONT_PX as i32 + 12 + y_tick_w.ceil() as i32 + gap + tick_len;

    // Fewer x labels when long labels would not fit side by side.
    let avail_w = (PLOT_WIDTH as i32 - left_band - right_margin) as f32;
    let mut n_x_labels = N_TICK_LABELS;
    let mut x_ticks = ticks(&x_keys, x, n_x_labels);
    while n_x_labels > 2 {
        let widest = x_ticks
            .iter()
            .map(|(_, t)| painter.width(t, tick_px))
            .fold(0.0f32, f32::max);
        if (widest + 14.0) * x_ticks.len() as f32 <= avail_w {
            break;
        }
        n_x_labels -= 1;
        x_ticks = ticks(&x_keys, x, n_x_labels);
    }
    let bottom_band = tick_len + gap + TICK_FONT_PX as i32 + 14 + AXIS_DESC_FONT_PX as i32 + 12;

    let root = BitMapBackend::with_buffer(pixels, (PLOT_WIDTH, PLOT_HEIGHT)).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let mut chart = ChartBuilder::on(&root)
        .margin_top(top)
        .margin_right(right_margin)
        .x_label_area_size(bottom_band)
        .y_label_area_size(left_band)
        .build_cartesian_2d(x_coord, y_coord)
        .map_err(err)?;

    let no_label = |_: &f64| String::new();
    chart
        .configure_mesh()
        .x_labels(n_x_labels)
        .y_labels(N_TICK_LABELS)
        .x_label_formatter(&no_label)
        .y_label_formatter(&no_label)
        .set_all_tick_mark_size(tick_len)
        .bold_line_style(BLACK.mix(0.16))
        .light_line_style(BLACK.mix(0.05))
        .axis_style(BLACK.mix(0.85))
        .draw()
        .map_err(err)?;

    for p in prepared {
        let color = PALETTE[p.index % PALETTE.len()];
        let line = color.stroke_width(LINE_WIDTH);
        let dot = color.filled();
        let runs = &p.runs;
        let style = p.series.style;
        match style {
            SeriesStyle::Line | SeriesStyle::LineWithMarkers => {
                chart
                    .draw_series(
                        runs.iter()
                            .filter(|r| r.len() > 1)
                            .map(|r| PathElement::new(r.clone(), line)),
                    )
                    .map_err(err)?;
            }
            SeriesStyle::DashedLine => {
                chart
                    .draw_series(runs.iter().filter(|r| r.len() > 1).flat_map(|r| {
                        DashedLineSeries::new(r.iter().copied(), DASH_PX, DASH_GAP_PX, line)
                    }))
                    .map_err(err)?;
            }
            SeriesStyle::Markers => {}
        }
        // Markers; for pure line styles only isolated single points, which a line cannot show.
        let with_markers = matches!(style, SeriesStyle::Markers | SeriesStyle::LineWithMarkers);
        chart
            .draw_series(
                runs.iter()
                    .filter(|r| with_markers || r.len() == 1)
                    .flatten()
                    .map(|&pt| Circle::new(pt, MARKER_RADIUS, dot)),
            )
            .map_err(err)?;
    }

    let (px_range, py_range) = chart.plotting_area().get_pixel_range();
    let (left, right) = (px_range.start, px_range.end - 1);
    let (upper, lower) = (py_range.start, py_range.end - 1);
    // Frame around the plotting area.
    root.draw(&Rectangle::new(
        [(left, upper), (right, lower)],
        BLACK.mix(0.85),
    ))
    .map_err(err)?;

    // Tick labels, with a typographic minus sign.
    let minus = |t: &str| t.replace('-', "\u{2212}");
    for (v, text) in &x_ticks {
        let (sx, _) = chart.backend_coord(&(*v, y.lo));
        jobs.push(TextJob {
            text: minus(text),
            px: tick_px,
            x: sx as f32,
            y: (lower + tick_len + gap) as f32,
            h: HAlign::Center,
            v: VAlign::Top,
            vertical: false,
        });
    }
    for (v, text) in &y_ticks {
        let (_, sy) = chart.backend_coord(&(x.lo, *v));
        jobs.push(TextJob {
            text: minus(text),
            px: tick_px,
            x: (left - tick_len - gap) as f32,
            y: sy as f32,
            h: HAlign::Right,
            v: VAlign::Center,
            vertical: false,
        });
    }

    // Title and axis names.
    let centre_x = 0.5 * (left + right) as f32;
    let centre_y = 0.5 * (upper + lower) as f32;
    if !spec.title.is_empty() {
        jobs.push(TextJob {
            text: spec.title.clone(),
            px: TITLE_FONT_PX as f32,
            x: centre_x,
            y: 0.5 * upper as f32,
            h: HAlign::Center,
            v: VAlign::Center,
            vertical: false,
        });
    }
    jobs.push(TextJob {
        text: spec.x_label.clone(),
        px: AXIS_DESC_FONT_PX as f32,
        x: centre_x,
        y: (lower + tick_len + gap + TICK_FONT_PX as i32 + 14) as f32,
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

    // Legend box in the emptiest corner.
    let entries: Vec<&Prepared<'_>> = prepared
        .iter()
        .filter(|p| !p.series.label.is_empty())
        .collect();
    if !entries.is_empty() {
        let legend_px = LEGEND_FONT_PX as f32;
        let text_w = entries
            .iter()
            .map(|p| painter.width(&p.series.label, legend_px))
            .fold(0.0f32, f32::max)
            .ceil() as i32;
        let pad = 10;
        let row_h = (LEGEND_FONT_PX * 1.45).round() as i32;
        let box_w = pad + LEGEND_SAMPLE_PX + 8 + text_w + pad;
        let box_h = pad + row_h * entries.len() as i32 + pad - 4;
        let inset = 10;
        let plot_w = f64::from((right - left).max(1));
        let plot_h = f64::from((lower - upper).max(1));
        let corner = legend_corner(
            prepared,
            x,
            y,
            f64::from(box_w + inset) / plot_w,
            f64::from(box_h + inset) / plot_h,
        );
        let bx = if corner.right {
            right - inset - box_w
        } else {
            left + inset
        };
        let by = if corner.top {
            upper + inset
        } else {
            lower - inset - box_h
        };
        root.draw(&Rectangle::new(
            [(bx, by), (bx + box_w, by + box_h)],
            WHITE.mix(0.9).filled(),
        ))
        .map_err(err)?;
        root.draw(&Rectangle::new(
            [(bx, by), (bx + box_w, by + box_h)],
            BLACK.mix(0.35),
        ))
        .map_err(err)?;
        for (row, p) in entries.iter().enumerate() {
            let color = PALETTE[p.index % PALETTE.len()];
            let line = color.stroke_width(LINE_WIDTH);
            let cy = by + pad - 2 + row_h * row as i32 + row_h / 2;
            let x0 = bx + pad;
            let x1 = x0 + LEGEND_SAMPLE_PX;
            match p.series.style {
                SeriesStyle::Line | SeriesStyle::LineWithMarkers => {
                    root.draw(&PathElement::new(vec![(x0, cy), (x1, cy)], line))
                        .map_err(err)?;
                }
                SeriesStyle::DashedLine => {
                    root.draw(&PathElement::new(vec![(x0, cy), (x0 + DASH_PX, cy)], line))
                        .map_err(err)?;
                    root.draw(&PathElement::new(
                        vec![(x0 + DASH_PX + DASH_GAP_PX, cy), (x1, cy)],
                        line,
                    ))
                    .map_err(err)?;
                }
                SeriesStyle::Markers => {}
            }
            if matches!(
                p.series.style,
                SeriesStyle::Markers | SeriesStyle::LineWithMarkers
            ) {
                root.draw(&Circle::new(
                    ((x0 + x1) / 2, cy),
                    MARKER_RADIUS,
                    color.filled(),
                ))
                .map_err(err)?;
            }
            jobs.push(TextJob {
                text: p.series.label.clone(),
                px: legend_px,
                x: (x1 + 8) as f32,
                y: cy as f32,
                h: HAlign::Left,
                v: VAlign::Center,
                vertical: false,
            });
        }
    }

    drop(chart);
    root.present().map_err(err)?;
    Ok(jobs)
}

/// Encodes `pixels` (`width x height`, tightly packed RGB) as a PNG into a temporary file next to `path` and renames it to `path`.
pub(crate) fn write_atomically(
    path: &Path,
    pixels: &[u8],
    width: u32,
    height: u32,
) -> Result<(), PlotError> {
    let io_err = |p: &Path| {
        let p = p.to_path_buf();
        move |source| PlotError::Io { path: p, source }
    };
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    std::fs::create_dir_all(dir).map_err(io_err(dir))?;

    let file_name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "plot".to_string());
    let prefix = format!(".{file_name}.");
    let mut builder = tempfile::Builder::new();
    builder.prefix(&prefix).suffix(".tmp");
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o644));
    }
    let mut tmp = builder.tempfile_in(dir).map_err(io_err(dir))?;
    let tmp_path = tmp.path().to_path_buf();

    {
        let mut out = BufWriter::new(tmp.as_file_mut());
        let mut encoder = png::Encoder::new(&mut out, width, height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_adaptive_filter(png::AdaptiveFilterType::Adaptive);
        let encode_err = |e: png::EncodingError| match e {
            png::EncodingError::IoError(source) => PlotError::Io {
                path: tmp_path.clone(),
                source,
            },
            other => PlotError::Backend(format!("{}: PNG encoding: {other}", path.display())),
        };
        let mut writer = encoder.write_header().map_err(encode_err)?;
        writer.write_image_data(pixels).map_err(encode_err)?;
        writer.finish().map_err(encode_err)?;
        out.flush().map_err(io_err(&tmp_path))?;
    }
    tmp.as_file().sync_all().map_err(io_err(&tmp_path))?;
    // On failure the returned temporary file is dropped, which deletes it.
    tmp.persist(path).map_err(|e| PlotError::Io {
        path: path.to_path_buf(),
        source: e.error,
    })?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn axis_range(min: f64, max: f64, log: bool) -> std::ops::Range<f64> {
        let a = Axis::fit(min, max, log);
        a.lo..a.hi
    }

    const PNG_SIGNATURE: [u8; 8] = [0x89, b'P', b'N', b'G', 0x0D, 0x0A, 0x1A, 0x0A];

    fn assert_png(path: &Path) -> Vec<u8> {
        let bytes = std::fs::read(path).expect("read png");
        assert_eq!(bytes[..8], PNG_SIGNATURE, "{} is not a PNG", path.display());
        assert!(
            bytes.len() > 5_000,
            "suspiciously small PNG: {} bytes",
            bytes.len()
        );
        let decoder = png::Decoder::new(bytes.as_slice());
        let reader = decoder.read_info().expect("decode png header");
        let info = reader.info();
        assert_eq!((info.width, info.height), (PLOT_WIDTH, PLOT_HEIGHT));
        bytes
    }

    fn leftover_temp_files(dir: &Path) -> Vec<String> {
        std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.ends_with(".tmp"))
            .collect()
    }

    /// Cantilever-like sample: simulated tip deflection against an analytic reference.
    fn sample_spec() -> PlotSpec {
        let t: Vec<f64> = (0..=200).map(|i| f64::from(i) * 0.005).collect();
        let reference: Vec<(f64, f64)> = t
            .iter()
            .map(|&t| {
                (
                    t,
                    -0.05 * (1.0 - (2.0 * std::f64::consts::PI * 1.5 * t).cos()),
                )
            })
            .collect();
        let sim: Vec<(f64, f64)> = t
            .iter()
            .map(|&t| {
                let w = 2.0 * std::f64::consts::PI * 1.47 * t;
                (t, -0.05 * (1.0 - w.cos()) * (1.0 - 0.04 * t))
            })
            .collect();
        let coarse: Vec<(f64, f64)> = (0..=20)
            .map(|i| {
                let t = f64::from(i) * 0.05;
                (
                    t,
                    -0.05 * (1.0 - (2.0 * std::f64::consts::PI * 1.4 * t).cos()),
                )
            })
            .collect();
        PlotSpec {
            title: "Cantilever tip deflection".into(),
            x_label: "time t [s]".into(),
            y_label: "tip deflection w [m]".into(),
            log_x: false,
            log_y: false,
            series: vec![
                PlotSeries::new("TLSPH, h = 0.01 m", sim, SeriesStyle::Line),
                PlotSeries::new(
                    "analytic (Euler-Bernoulli)",
                    reference,
                    SeriesStyle::DashedLine,
                ),
                PlotSeries::new("TLSPH, h = 0.04 m", coarse, SeriesStyle::LineWithMarkers),
            ],
        }
    }

    fn loglog_spec() -> PlotSpec {
        let mut spec = PlotSpec::new(
            "Convergence: L2 error vs wall time",
            "wall time [s]",
            "relative L2 error",
        );
        spec.log_x = true;
        spec.log_y = true;
        let runs = |c: f64, order: f64| -> Vec<(f64, f64)> {
            (0..6)
                .map(|i| {
                    let n = 2f64.powi(i + 3);
                    (c * n.powi(2) * 1e-3, 0.3 * n.powf(-order))
                })
                .collect()
        };
        spec.series = vec![
            PlotSeries::new("Wendland C2", runs(1.0, 2.0), SeriesStyle::LineWithMarkers),
            PlotSeries::new("cubic spline", runs(0.6, 1.5), SeriesStyle::LineWithMarkers),
            PlotSeries::new(
                "reference slope 2",
                vec![(0.1, 1e-3), (60.0, 2.8e-9)],
                SeriesStyle::DashedLine,
            ),
            PlotSeries::new(
                "measured (with a NaN and a zero)",
                vec![
                    (0.2, 0.01),
                    (0.5, f64::NAN),
                    (2.0, 0.0),
                    (5.0, 1e-4),
                    (20.0, 2e-5),
                ],
                SeriesStyle::Markers,
            ),
        ];
        spec
    }

    #[test]
    fn writes_valid_png() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("sample.png");
        write_png(&path, &sample_spec()).unwrap();
        assert_png(&path);
        assert!(leftover_temp_files(dir.path()).is_empty());
        if let Some(dir) = std::env::var_os("TLSPH_PLOT_SAMPLES") {
            std::fs::copy(&path, Path::new(&dir).join("plot_sample.png")).unwrap();
        }
    }

    #[test]
    fn log_log_plot_works() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("loglog.png");
        write_png(&path, &loglog_spec()).unwrap();
        assert_png(&path);
        if let Some(dir) = std::env::var_os("TLSPH_PLOT_SAMPLES") {
            std::fs::copy(&path, Path::new(&dir).join("plot_loglog.png")).unwrap();
        }
    }

    #[test]
    fn semi_log_axes_work() {
        let dir = tempfile::tempdir().unwrap();
        let mut spec = PlotSpec::new("energy decay", "step", "kinetic energy [J]");
        spec.log_y = true;
        spec.series.push(PlotSeries::new(
            "E_kin",
            (0..100)
                .map(|i| (f64::from(i), (-0.1 * f64::from(i)).exp()))
                .collect(),
            SeriesStyle::Line,
        ));
        let path = dir.path().join("semilogy.png");
        write_png(&path, &spec).unwrap();
        assert_png(&path);
        spec.log_x = true;
        spec.log_y = false;
        let path = dir.path().join("semilogx.png");
        write_png(&path, &spec).unwrap();
        assert_png(&path);
    }

    #[test]
    fn no_drawable_data_is_an_error() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("sub").join("none.png");
        let mut spec = PlotSpec::new("t", "x", "y");
        let err = write_png(&path, &spec).unwrap_err();
        assert!(matches!(err, PlotError::NoData { .. }), "{err:?}");
        assert!(err.to_string().contains("none.png"), "{err}");

        spec.series
            .push(PlotSeries::new("empty", vec![], SeriesStyle::Line));
        spec.series.push(PlotSeries::new(
            "bad",
            vec![(f64::NAN, 1.0), (1.0, f64::INFINITY)],
            SeriesStyle::Markers,
        ));
        assert!(matches!(
            write_png(&path, &spec),
            Err(PlotError::NoData { .. })
        ));

        spec.log_y = true;
        spec.series.push(PlotSeries::new(
            "non-positive",
            vec![(1.0, 0.0), (2.0, -3.0)],
            SeriesStyle::Line,
        ));
        assert!(matches!(
            write_png(&path, &spec),
            Err(PlotError::NoData { .. })
        ));
        assert!(!path.exists());
    }

    #[test]
    fn degenerate_ranges_still_draw() {
        let dir = tempfile::tempdir().unwrap();
        let cases = [
            ("single_point", vec![(1.0, 2.0)]),
            ("const_x", vec![(3.0, 1.0), (3.0, 2.0), (3.0, 5.0)]),
            ("const_y", vec![(0.0, 7.0), (1.0, 7.0), (2.0, 7.0)]),
            ("zeros", vec![(0.0, 0.0), (0.0, 0.0)]),
        ];
        for (name, points) in cases {
            for log in [false, true] {
                let mut spec = PlotSpec::new(name, "x", "y");
                spec.log_x = log;
                spec.log_y = log;
                spec.series
                    .push(PlotSeries::new(name, points.clone(), SeriesStyle::Line));
                let path = dir.path().join(format!("{name}_{log}.png"));
                let result = write_png(&path, &spec);
                if log && name == "zeros" {
                    assert!(matches!(result, Err(PlotError::NoData { .. })));
                } else {
                    result.unwrap();
                    assert_png(&path);
                }
            }
        }
    }

    #[test]
    fn replaces_existing_file_atomically_and_creates_dirs() {
        let dir = tempfile::tempdir().unwrap();
        let sub = dir.path().join("a").join("b");
        let path = sub.join("plot.png");
        write_png(&path, &sample_spec()).unwrap();
        let first = assert_png(&path);

        std::fs::write(&path, b"stale contents").unwrap();
        write_png(&path, &loglog_spec()).unwrap();
        let second = assert_png(&path);
        assert_ne!(first, second);
        assert!(
            leftover_temp_files(&sub).is_empty(),
            "{:?}",
            leftover_temp_files(&sub)
        );
        let names: Vec<_> = std::fs::read_dir(&sub)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names, vec![std::ffi::OsString::from("plot.png")]);
    }

    #[test]
    fn io_error_names_the_path() {
        let dir = tempfile::tempdir().unwrap();
        let blocker = dir.path().join("not_a_dir");
        std::fs::write(&blocker, b"x").unwrap();
        let path = blocker.join("plot.png");
        let err = write_png(&path, &sample_spec()).unwrap_err();
        assert!(matches!(err, PlotError::Io { .. }), "{err:?}");
        assert!(err.to_string().contains("not_a_dir"), "{err}");
    }

    #[test]
    fn parallel_writes_are_safe() {
        let dir = tempfile::tempdir().unwrap();
        std::thread::scope(|s| {
            for i in 0..4 {
                let path = dir.path().join(format!("p{i}.png"));
                s.spawn(move || write_png(&path, &sample_spec()).unwrap());
            }
        });
        for i in 0..4 {
            assert_png(&dir.path().join(format!("p{i}.png")));
        }
    }

    #[test]
    fn axis_ranges() {
        // Linear: 5 % margin each side.
        let r = axis_range(0.0, 10.0, false);
        assert!(
            (r.start + 0.5).abs() < 1e-12 && (r.end - 10.5).abs() < 1e-12,
            "{r:?}"
        );
        // Degenerate linear ranges widen.
        let r = axis_range(7.0, 7.0, false);
        assert!(r.start < 7.0 && r.end > 7.0);
        let r = axis_range(0.0, 0.0, false);
        assert_eq!(r, -1.0..1.0);
        // Log: rounded out to 1-2-5 values, at least two decades marked.
        let close = |r: std::ops::Range<f64>, lo: f64, hi: f64| {
            assert!(
                (r.start / lo - 1.0).abs() < 1e-8 && (r.end / hi - 1.0).abs() < 1e-8,
                "{r:?}"
            );
            assert!(r.start <= lo && r.end >= hi, "{r:?}");
        };
        close(axis_range(1.0, 1000.0, true), 0.5, 2000.0);
        close(axis_range(3.0, 8.0, true), 1.0, 10.0);
        close(axis_range(1.0, 1.0, true), 0.1, 10.0);
        let r = axis_range(1e-300, 1e300, true);
        assert!(r.start > 0.0 && r.end.is_finite());
    }

    #[test]
    fn tick_labels_are_compact() {
        let lin = Axis {
            lo: -0.105,
            hi: 1.05,
            log: false,
        };
        assert_eq!(tick_label(&lin, 0.30000000000000004), "0.3");
        assert_eq!(tick_label(&lin, 1e-17), "0");
        assert_eq!(tick_label(&lin, -0.1), "-0.1");
        let small = Axis {
            lo: 0.0,
            hi: 5e-4,
            log: false,
        };
        assert_eq!(tick_label(&small, 1.5e-4), "1.5e-4");
        let log = Axis {
            lo: 1e-6,
            hi: 1.0,
            log: true,
        };
        assert_eq!(tick_label(&log, 1e-3), "1e-3");
        assert_eq!(tick_label(&log, 2e-5), "2e-5");
        let log = Axis {
            lo: 0.1,
            hi: 100.0,
            log: true,
        };
        assert_eq!(tick_label(&log, 0.2), "0.2");
        assert_eq!(tick_label(&log, 30.0), "30");
    }
}
