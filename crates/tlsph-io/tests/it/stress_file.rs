//! `initial_stress_file`: an initial stress field read from a CSV table of sample points.

use std::fmt::Write as _;
use std::path::Path;
use tlsph_io::{DimensionModel, SceneError};
use tlsph_math::Tensor3;
use tlsph_solver::{Model, Simulation};

/// A 2D column 8 × 20 particles (ρ = 1, c = 1) held at its base under gravity g = 0.01,
/// started in equilibrium by the stress given in `stress` (lines of the body table).
fn column(stress: &str) -> String {
    format!(
        r#"
[simulation]
dimension = 2
formulation = "total-lagrangian-corrected"
kernel = "cubic-spline"
smoothing_factor = 1.3
cfl = 0.3
end_time = 1.0

[[material]]
name = "m"
model = "linear-elastic"
density = 1.0
youngs_modulus = 0.9
poisson_ratio = 0.25

[[body]]
name = "column"
material = "m"
spacing = 0.05
box = {{ min = [0.0, 0.0], max = [0.4, 1.0] }}
{stress}

[[boundary]]
name = "base"
body = "column"
box = {{ min = [-1.0, -1.0], max = [1.0, 0.05] }}
velocity = [0.0, 0.0]

[body_force]
acceleration = [0.0, -0.01]

[output]
dir = "out"
"#
    )
}

/// σ_yy = ρ g (y − H) with ρ = 1, g = 0.01, H = 1.
const GRADIENT: &str = "initial_stress = { yy = -0.01 }
initial_stress_gradient = { yy = [0.0, 0.01] }";

/// Writes `scene` and `table` (as `stress/field.csv`) into `dir` and loads the scene.
fn load_with_table(dir: &Path, scene: &str, table: &str) -> Result<tlsph_io::Scene, SceneError> {
    super::load_with_table(dir, scene, "stress/field.csv", table)
}

fn model_2d(scene: tlsph_io::Scene) -> Model<2> {
    match scene.model {
        DimensionModel::Two(m) => m,
        _ => unreachable!("a 2D scene"),
    }
}

/// The table `x, y, xx, yy, xy` of `stress` at `points` (Rust's shortest round-trip
/// formatting, so the numbers read back exactly).
fn table_of(points: &[tlsph_math::Vector<2>], stress: impl Fn(usize) -> Tensor3) -> String {
    let mut table = String::from("# a comment line\nx, y, yy, xx, xy\n");
    for (k, x) in points.iter().enumerate() {
        let s = stress(k);
        writeln!(
            table,
            "{}, {}, {}, {}, {}",
            x.x,
            x.y,
            s[(1, 1)],
            s[(0, 0)],
            s[(0, 1)]
        )
        .unwrap();
    }
    table
}

/// The column declared with its linear gravity stress (`GRADIENT`), and that field σ(X).
fn declared_column() -> (Model<2>, impl Fn(&tlsph_math::Vector<2>) -> Tensor3) {
    let model = model_2d(tlsph_io::parse_scene(&column(GRADIENT), "column.toml").unwrap());
    let body = &model.bodies[0];
    let (at_origin, gradient) = (
        body.initial_stress.unwrap(),
        body.initial_stress_gradient.unwrap(),
    );
    let field =
        move |x: &tlsph_math::Vector<2>| tlsph_solver::linear_stress_at(at_origin, &gradient, x);
    (model, field)
}

#[test]
fn a_field_read_at_the_particles_runs_bit_identical_to_the_same_linear_field() {
    let dir = tempfile::tempdir().unwrap();
    let (linear, field_at) = declared_column();
    let body = &linear.bodies[0];
    let field = |k: usize| field_at(&body.positions[k]);
    let table = table_of(&body.positions, field);
    // The path is relative to the scene file's folder, not the working directory.
    let scene = column("initial_stress_file = { path = \"stress/field.csv\" }");
    let from_file = model_2d(load_with_table(dir.path(), &scene, &table).unwrap());
    let stresses = from_file.bodies[0].initial_stresses.clone().unwrap();
    assert_eq!(stresses.len(), body.positions.len());
    assert!((0..stresses.len()).all(|k| stresses[k] == field(k)));

    // Same field, same run: every stress and displacement agrees to the bit after 100 steps.
    let mut a = Simulation::new(linear).unwrap();
    let mut b = Simulation::new(from_file).unwrap();
    assert!(a.stresses() == b.stresses());
    for _ in 0..100 {
        a.step().unwrap();
        b.step().unwrap();
    }
    assert!(a.stresses() == b.stresses());
    assert!(a.displacements() == b.displacements());
    // And the comparison is not of two empty states: the weight's stress is still there,
    // from about −ρgH at the base to about 0 at the top (the rows at the free ends relax).
    let sigma_yy: Vec<f64> = b.stresses().iter().map(|s| s[(1, 1)]).collect();
    let (lo, hi) = sigma_yy
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), s| {
            (l.min(*s), h.max(*s))
        });
    assert!(lo < -0.008 && hi > -0.001, "σ_yy from {lo} to {hi}");
}

#[test]
fn each_particle_takes_the_stress_of_its_nearest_sample() {
    // A coarser table (pitch 0.1, twice the spacing, offset by half a spacing so no particle is
    // equidistant from two samples) of a non-linear field σ_xx = X², σ_xy = XY.
    let dir = tempfile::tempdir().unwrap();
    let samples: Vec<tlsph_math::Vector<2>> = (0..5)
        .flat_map(|i| {
            (0..11).map(move |j| tlsph_math::Vector::<2>::new(0.1 * i as f64, 0.1 * j as f64))
        })
        .map(|p| p + tlsph_math::Vector::<2>::new(0.05, 0.05))
        .collect();
    let field = |x: &tlsph_math::Vector<2>| {
        Tensor3::new(
            x.x * x.x,
            x.x * x.y,
            0.0,
            x.x * x.y,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
        )
    };
    let table = table_of(&samples, |k| field(&samples[k]));
    // Particles sit at 0.025 + 0.05 k; the nearest sample is within 0.025 √2 per particle.
    let scene = column("initial_stress_file = { path = \"stress/field.csv\" }");
    let model = model_2d(load_with_table(dir.path(), &scene, &table).unwrap());
    let body = &model.bodies[0];
    let stresses = body.initial_stresses.as_ref().unwrap();
    for (x, stress) in body.positions.iter().zip(stresses) {
        let nearest = samples
            .iter()
            .min_by(|a, b| (*a - x).norm().total_cmp(&(*b - x).norm()))
            .unwrap();
        assert!((nearest - x).norm() < 0.036, "{x:?}");
        assert_eq!(*stress, field(nearest), "particle at {x:?}");
    }
    // The run starts from it.
    let sim = Simulation::new(model).unwrap();
    assert_eq!(sim.stresses()[0][(0, 0)], 0.05 * 0.05);

    // A reach shorter than the distance to the nearest sample (0.025 √2) is refused with the
    // particle named.
    let short = column("initial_stress_file = { path = \"stress/field.csv\", reach = 0.03 }");
    let e = load_with_table(dir.path(), &short, &table).unwrap_err();
    assert_eq!(e.field, "body[column].initial_stress_file", "{e}");
    assert!(
        e.message
            .contains("particle 0 at [0.025, 0.025] has no sample within reach"),
        "{e}"
    );
}

#[test]
fn a_coarse_table_mapped_linearly_gives_the_column_its_linear_gravity_stress() {
    // The column's σ_yy = ρg(y − H) sampled at 3 × 6 points (pitch 0.2, four spacings; the
    // corners of the column included) and fitted linearly within reach 0.3: every particle's
    // stress is the declared linear field to round-off (values of order 10⁻², so 10⁻¹⁵ is
    // about 500 ulps), where the nearest sample is off by up to ρg × 0.1 = 10⁻³.
    let dir = tempfile::tempdir().unwrap();
    let (linear, field) = declared_column();
    let body = &linear.bodies[0];
    let samples: Vec<tlsph_math::Vector<2>> = (0..3)
        .flat_map(|i| {
            (0..6).map(move |j| tlsph_math::Vector::<2>::new(0.2 * i as f64, 0.2 * j as f64))
        })
        .collect();
    let table = table_of(&samples, |k| field(&samples[k]));
    let largest_error = |interpolation: &str| {
        let scene = column(&format!(
            "initial_stress_file = {{ path = \"stress/field.csv\", reach = 0.3, interpolation = \"{interpolation}\" }}"
        ));
        let model = model_2d(load_with_table(dir.path(), &scene, &table).unwrap());
        let stresses = model.bodies[0].initial_stresses.clone().unwrap();
        (body.positions.iter().zip(&stresses))
            .map(|(x, s)| (s - field(x)).abs().max())
            .fold(0.0, f64::max)
    };
    let linear_error = largest_error("linear");
    assert!(linear_error < 1e-15, "linear: {linear_error:e}");
    let nearest_error = largest_error("nearest");
    assert!(nearest_error > 5e-4, "nearest: {nearest_error:e}");
}

#[test]
fn stress_file_errors_name_the_file_line_and_field() {
    let dir = tempfile::tempdir().unwrap();
    let key = "initial_stress_file = { path = \"stress/field.csv\" }";
    // One sample, at the column's centre: the particles near the base are beyond its reach.
    let good_rows = "0.2, 0.5, -0.01\n";
    for (scene_key, table, field, message) in [
        (
            key,
            "x, y, yy\n0.0, 0.0, nan\n",
            "path",
            "line 2: `yy` must be a finite number",
        ),
        // Comment and blank lines count: the bad row is the file's line 5.
        (
            key,
            "# header next\nx, y, yy\n\n# a row next\n0.0, 0.0, 1.0, 2.0\n",
            "path",
            "line 5: 4 cells, but the header names 3 columns",
        ),
        (key, "# only a comment\n", "path", "no header line"),
        (
            key,
            "x, y, yy\n0.0, zero, 1.0\n",
            "path",
            "`y` must be a finite number, got `zero`",
        ),
        (key, "x, yy\n0.0, 1.0\n", "path", "no column `y`"),
        (key, "x, y, pressure\n", "path", "unknown column `pressure`"),
        (key, "x, y, yy, yy\n", "path", "appears twice"),
        // The template `tlsph particles` writes, before a stress column is added.
        (
            key,
            "x,y\n0.025,0.025\n",
            "path",
            "names no field column; give at least one of xx, yy, zz, xy, yz, xz",
        ),
        (key, "x, y, yy\n", "path", "no sample rows"),
        (
            key,
            "x, y, yz\n0, 0, 1\n",
            "",
            "`yz` is not a stress component of a 2D scene",
        ),
        (
            "initial_stress_file = { path = \"stress/missing.csv\" }",
            "",
            "path",
            "cannot read",
        ),
        (
            "initial_stress_file = { path = \"stress/field.csv\", reach = -1.0 }",
            "",
            "reach",
            "",
        ),
        (
            "initial_stress_file = { path = \"stress/field.csv\", range = 1.0 }",
            "",
            "",
            "unknown field `range`",
        ),
        (
            key,
            &format!("x, y, yy\n{good_rows}"),
            "",
            "particle 0 at [0.025, 0.025] has no sample within reach 5e-2",
        ),
        (
            &format!("{key}\ninitial_stress = {{ yy = -0.01 }}"),
            &format!("x, y, yy\n{good_rows}"),
            "",
            "`initial_stress` cannot be declared with it",
        ),
    ] {
        let scene = column(scene_key);
        let e = load_with_table(dir.path(), &scene, table).unwrap_err();
        let expected_field = match field {
            "" if message.starts_with("unknown field") => String::new(),
            "" => "body[column].initial_stress_file".to_string(),
            sub => format!("body[column].initial_stress_file.{sub}"),
        };
        assert_eq!(e.field, expected_field, "{table}: {e}");
        assert!(e.message.contains(message), "{table}: {e}");
        // The error is at the key's line of the scene file.
        let key_line = scene
            .lines()
            .position(|l| l.starts_with("initial_stress_file"))
            .unwrap()
            + 1;
        assert_eq!(e.line, Some(key_line), "{e}");
        assert!(e.file.ends_with("scene.toml"), "{e}");
        if field == "path" && !message.contains("cannot read") {
            assert!(e.message.contains("field.csv"), "names the table: {e}");
        }
    }
}

#[test]
fn a_stress_file_is_refused_where_an_initial_stress_is() {
    let dir = tempfile::tempdir().unwrap();
    let key = "initial_stress_file = { path = \"stress/field.csv\" }";
    let rows: String = (0..8)
        .flat_map(|i| (0..20).map(move |j| (0.025 + 0.05 * i as f64, 0.025 + 0.05 * j as f64)))
        .map(|(x, y)| format!("{x}, {y}, {}\n", if y > 0.9 { 0.5 } else { 0.0 }))
        .collect();
    let table = format!("x, y, xx\n{rows}");
    // Elastic–plastic with σ_y0 = 0.4: the rows above y = 0.9 (σ_xx = 0.5) are outside.
    let plastic = column(key).replace(
        "model = \"linear-elastic\"",
        "model = \"elastic-plastic\"\nyield_stress = 0.4",
    );
    let e = load_with_table(dir.path(), &plastic, &table).unwrap_err();
    assert_eq!(e.field, "body[column].initial_stress_file", "{e}");
    assert!(
        e.message.contains("takes the particle at [0.025, 0.925]")
            && e.message.contains("line 20 of")
            && e.message.contains("yield surface"),
        "{e}"
    );
    // A fitted stress is checked too, and the message says where it comes from.
    let fitted = plastic.replace(
        "path = \"stress/field.csv\" }",
        "path = \"stress/field.csv\", interpolation = \"linear\" }",
    );
    assert_ne!(fitted, plastic);
    let e = load_with_table(dir.path(), &fitted, &table).unwrap_err();
    assert_eq!(e.field, "body[column].initial_stress_file", "{e}");
    assert!(
        e.message.contains("fitted to ")
            && e.message.contains("samples of `")
            && e.message.contains("the nearest on line")
            && e.message.contains("yield surface"),
        "{e}"
    );
    // A damage model keeps its own effective stress, which starts at zero.
    let damaged = column(key).replace(
        "model = \"linear-elastic\"",
        "model = \"elastic-plastic\"\nyield_stress = 0.4\ndamage = { model = \"peerlings\", kappa0 = 0.001, kappa_c = 0.01 }",
    );
    let e =
        load_with_table(dir.path(), &damaged, &table.replace(", 0.5\n", ", 0.0\n")).unwrap_err();
    assert_eq!(e.field, "body[column].initial_stress_file", "{e}");
    assert!(e.message.contains("damage model"), "{e}");
    // The Green–Lagrange path computes stress from F alone.
    let gl = column(key).replace("cfl = 0.3", "cfl = 0.3\nstress_update = \"green-lagrange\"");
    let e = load_with_table(dir.path(), &gl, &table).unwrap_err();
    assert_eq!(e.field, "body[column].initial_stress_file", "{e}");
    assert!(e.message.contains("jaumann-rate"), "{e}");
}

/// Largest kinetic energy over `steps` steps of a plane-strain disc (radius 1, Δx = 0.05,
/// E = 1, ν = 0.3, ρ = 1) that starts at rest with the stress `field(x, y)` read from a
/// table at its particles, and the field's strain energy ∫ σ:C⁻¹:σ / 2 dV (in-plane, plane
/// strain) for scale.
fn disc_ringing(field: impl Fn(f64, f64) -> [f64; 3], spacing: f64, steps: usize) -> (f64, f64) {
    let dir = tempfile::tempdir().unwrap();
    let scene = |stress: &str| {
        format!(
            r#"
[simulation]
dimension = 2
formulation = "total-lagrangian-corrected"
kernel = "cubic-spline"
smoothing_factor = 1.3
cfl = 0.3
end_time = 100.0

[[material]]
name = "m"
model = "linear-elastic"
density = 1.0
youngs_modulus = 1.0
poisson_ratio = 0.3

[[body]]
name = "disc"
material = "m"
spacing = {spacing}
disc = {{ centre = [0.0, 0.0], radius = 1.0 }}
{stress}

[output]
dir = "out"
"#
        )
    };
    let bare = model_2d(tlsph_io::parse_scene(&scene(""), "disc.toml").unwrap());
    let mut table = String::from("x,y,xx,yy,xy\n");
    let (e, nu) = (1.0, 0.3);
    let mut strain_energy = 0.0;
    for (p, v) in bare.bodies[0].positions.iter().zip(&bare.bodies[0].volumes) {
        let [xx, yy, xy] = field(p.x, p.y);
        writeln!(table, "{},{},{xx},{yy},{xy}", p.x, p.y).unwrap();
        // Plane strain with σ_zz = ν(σ_xx + σ_yy): w = [(1 − ν²)(σxx² + σyy²) − 2ν(1 + ν)σxxσyy
        // + 2(1 + ν)σxy²] / (2E).
        let w = ((1.0 - nu * nu) * (xx * xx + yy * yy) - 2.0 * nu * (1.0 + nu) * xx * yy
            + 2.0 * (1.0 + nu) * xy * xy)
            / (2.0 * e);
        strain_energy += w * v;
    }
    let model = model_2d(
        load_with_table(
            dir.path(),
            &scene("initial_stress_file = { path = \"stress/field.csv\" }"),
            &table,
        )
        .unwrap(),
    );
    let mut sim = Simulation::new(model).unwrap();
    let mut largest: f64 = 0.0;
    for _ in 0..steps {
        sim.step().unwrap();
        largest = largest.max(sim.diagnostics().kinetic);
    }
    (largest, strain_energy)
}

#[test]
fn a_self_equilibrated_residual_stress_keeps_a_disc_at_rest() {
    // The residual stress of a disc with a parabolic eigenstrain (e.g. quenched):
    // σ_rr = A(1 − r²), σ_θθ = A(1 − 3r²), i.e. σ_xx = A(1 − x² − 3y²),
    // σ_yy = A(1 − 3x² − y²), σ_xy = 2Axy. It satisfies ∇·σ = 0 and σ_rr(1) = 0, so the disc
    // should not move. The same magnitude without the hoop part, σ_xx = σ_yy = A(1 − r²),
    // is traction-free but not in equilibrium inside (∇·σ = −2A x): it rings.
    let a = 1e-3;
    let equilibrated = |x: f64, y: f64| {
        [
            a * (1.0 - x * x - 3.0 * y * y),
            a * (1.0 - 3.0 * x * x - y * y),
            2.0 * a * x * y,
        ]
    };
    let unbalanced = |x: f64, y: f64| {
        let s = a * (1.0 - x * x - y * y);
        [s, s, 0.0]
    };
    // 300 steps: t ≈ 5.3, about 2.6 transits of the diameter at c ≈ 1.16.
    let (at_rest, energy) = disc_ringing(equilibrated, 0.05, 300);
    let (ringing, _) = disc_ringing(unbalanced, 0.05, 300);
    let (at_rest_fine, _) = disc_ringing(equilibrated, 0.025, 600);
    // Measured: the unbalanced field's largest kinetic energy is 26 % of the field's strain
    // energy; the equilibrated one's is 18 % of that at Δx = 0.05, and 0.39 times as much
    // again at half the spacing. What is left is the discretisation error of ∇·σ at the free surface (the hoop
    // stress is −2A there), which falls with the spacing, while the ringing is physical.
    assert!(ringing > 0.1 * energy, "{ringing:e} vs {energy:e}");
    assert!(at_rest < 0.25 * ringing, "{at_rest:e} vs {ringing:e}");
    assert!(
        at_rest_fine < 0.6 * at_rest,
        "{at_rest_fine:e} vs {at_rest:e}"
    );
}
