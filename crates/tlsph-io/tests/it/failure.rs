//! Failure models in whole runs: the energy balance of a body that loses particles, and the
//! combinations a failure model cannot be used with, refused at their line.

use super::{error_of, line_of};
use tlsph_io::{parse_scene, run_scene};
use tlsph_solver::Diagnostics;

/// A quarter model of a steel sphere (Johnson–Cook strength, Mie–Grüneisen EOS) striking an
/// aluminium plate at 800 m/s. The plate (Johnson–Cook strength, Mie–Grüneisen EOS,
/// Johnson–Cook failure) loses a few hundred particles under the sphere. Parameters are the
/// usual published Johnson–Cook and shock-Hugoniot values for 4340 steel and 2024 aluminium.
const SPHERE_ON_PLATE: &str = r#"
[simulation]
dimension = 3
formulation = "total-lagrangian-corrected"
kernel = "cubic-spline"
smoothing_factor = 1.2
cfl = 0.3
end_time = 10.0e-6

[[material]]
name = "steel"
model = "johnson-cook"
density = 7830.0
youngs_modulus = 200.0e9
poisson_ratio = 0.29
a = 792.0e6
b = 510.0e6
n = 0.26
c = 0.014
m = 1.03
reference_strain_rate = 1.0
room_temperature = 293.0
melt_temperature = 1793.0
specific_heat = 477.0
eos = { model = "mie-gruneisen", sound_speed = 4569.0, s1 = 1.49, gamma0 = 2.17 }

[[material]]
name = "aluminium"
model = "johnson-cook"
density = 2700.0
youngs_modulus = 70.0e9
poisson_ratio = 0.33
a = 324.0e6
b = 114.0e6
n = 0.42
c = 0.002
m = 1.34
reference_strain_rate = 1.0
room_temperature = 293.0
melt_temperature = 925.0
specific_heat = 875.0
eos = { model = "mie-gruneisen", sound_speed = 5386.0, s1 = 1.339, gamma0 = 1.97 }
failure = { model = "johnson-cook", d = [-0.77, 1.45, -0.47, 0.0, 1.6] }

[[body]]
name = "ball"
material = "steel"
spacing = 0.5e-3
sphere = { centre = [0.0, 0.0, 3.6e-3], radius = 3.0e-3 }
clip = { min = [0.0, 0.0, 0.0], max = [1.0, 1.0, 1.0] }
velocity = [0.0, 0.0, -800.0]

[[body]]
name = "plate"
material = "aluminium"
spacing = 0.5e-3
box = { min = [0.0, 0.0, -3.0e-3], max = [8.0e-3, 8.0e-3, 0.0] }

[[symmetry_plane]]
axis = "x"
position = 0.0

[[symmetry_plane]]
axis = "y"
position = 0.0

[contact]
scale = 0.1
pairs = [["ball", "plate"]]

[bulk_viscosity]
quadratic = 1.5
linear = 0.06

[[boundary]]
name = "rim"
body = "plate"
box = { min = [7.5e-3, -1.0, -1.0], max = [1.0, 1.0, 1.0] }
fixed = true

[output]
energy_interval = 0.25e-6
"#;

#[test]
fn a_plate_that_loses_particles_under_an_eos_keeps_its_energy_balance() {
    // When failed particles leave, their neighbours' corrected gradients are rebuilt and the
    // estimate det F of an unchanged configuration jumps (by up to 28 % here). An equation of
    // state reads the density from J, so without the carried density (numerics.md §4.3) the
    // pressure jumped with no p dV booked: surviving particles then expanded to negative
    // internal energy and handed it to the kinetic energy. Measured before the fix: total
    // energy +0.29 % at the end with KE rising during penetration, and the energy carried out
    // by deleted particles −4.6 J; after: −0.012 % and +1.7 J.
    // The same plate with Grady–Kipp flaws instead of Johnson–Cook failure (the softening
    // damage of its elastic–plastic stress, numerics.md §9.2; k puts the plate's first flaw at
    // a tensile strain of 4.3e-3, 300 MPa) loses 265 particles with the same balance: worst
    // drift −1.8e-4.
    let flaws = "damage = { model = \"grady-kipp\", m = 9.0, k = 1.0363e28, seed = 3 }";
    let jc = "failure = { model = \"johnson-cook\", d = [-0.77, 1.45, -0.47, 0.0, 1.6] }";
    let with_flaws = SPHERE_ON_PLATE.replace(jc, flaws);
    assert_ne!(with_flaws, SPHERE_ON_PLATE);
    // And with both on the plate, a particle failing by whichever comes first: 294 fail
    // (284 by Johnson–Cook alone, 265 by the flaws alone), worst drift −1.8e-4. A particle one
    // mechanism fails is not failed again by the other, so more must fail than by either alone
    // (a shock-and-release history only adds ways to fail).
    let with_both = SPHERE_ON_PLATE.replace(jc, &format!("{jc}\n{flaws}"));
    let by_jc = plate_keeps_its_energy_balance(SPHERE_ON_PLATE);
    let by_flaws = plate_keeps_its_energy_balance(&with_flaws);
    let by_both = plate_keeps_its_energy_balance(&with_both);
    assert!(
        by_both > by_jc.max(by_flaws),
        "{by_both} failed with both, {by_jc} by Johnson–Cook, {by_flaws} by the flaws"
    );
}

/// Runs a sphere-on-plate scene and checks that the plate loses particles while the total
/// energy stays within 3e-4 of its start and the deleted particles carry out energy ≥ 0;
/// returns the number of failed particles.
fn plate_keeps_its_energy_balance(text: &str) -> usize {
    let scene = parse_scene(text, "sphere.toml").unwrap();
    let record = run_scene(&scene, &mut |_, _| {}).unwrap();
    assert!(record.failure.is_none(), "{:?}", record.failure);
    let last = record.diagnostics.last().unwrap();
    assert!(
        last.failed_particles > 100,
        "the plate must lose particles: {}",
        last.failed_particles
    );
    let e0 = record.diagnostics[0].total_energy();
    // Tolerance: the contact and bulk viscosity close to about 1e-4 of E0 without failure.
    // Measured worst drift: −1.8e-4 with the removal steps booked exactly
    // (`removal_steps_keep_the_energy_balance`); +4.8e-4
    // before that, when each removal step left its neighbours' share of the work unbooked.
    for d in &record.diagnostics {
        let drift = (d.total_energy() - e0) / e0;
        assert!(
            drift.abs() < 3e-4,
            "t = {:.2e}: total energy drifted by {drift:.2e}",
            d.time
        );
        let (_, deleted) = d
            .effect_energies
            .iter()
            .find(|(name, _)| name == "deleted_particles")
            .expect("a deleted-particle column");
        assert!(
            *deleted >= 0.0,
            "t = {:.2e}: failed particles carried out {deleted} J of internal energy",
            d.time
        );
    }
    last.failed_particles
}

/// A 1D bar of 100 particles squeezed homogeneously (v = −0.02 x, the three end particles on
/// each side held to that field) until the plastic strain of the free interior reaches the failure
/// limit: 94 particles fail in the same step. Every step is sampled. The test adds the six
/// held particles as `[[boundary]]` tables.
const SQUEEZED_BAR: &str = r#"
[simulation]
dimension = 1
formulation = "FORMULATION"
kernel = "cubic-spline"
smoothing_factor = 1.2
cfl = 0.3
end_time = 1.5

[[material]]
name = "m"
model = "elastic-plastic"
density = 1.0
youngs_modulus = 0.8333333333333334
poisson_ratio = 0.25
yield_stress = 0.002
failure = { model = "max-plastic-strain", limit = 0.01 }

[[body]]
name = "bar"
material = "m"
spacing = 0.01
box = { min = [0.0], max = [1.0] }
velocity_gradient = [[-0.02]]

[output]
energy_interval = 1.0e-9
"#;

/// How the total energy of a run of [`SQUEEZED_BAR`] moved, as fractions of its initial value:
/// the largest single-step jump before the first removal and in a removal step, and the
/// offset at the end and the largest offset over the run; with the number of failed
/// particles.
struct RemovalEnergy {
    before_failure: f64,
    removal: f64,
    end: f64,
    largest: f64,
    failed: usize,
}

/// Runs [`SQUEEZED_BAR`] with `formulation`, the failure line replaced by `failure` and the
/// bar deformed at the rate `rate` (−0.02 squeezes it).
fn removal_energy(formulation: &str, failure: &str, rate: f64) -> RemovalEnergy {
    let mut text = SQUEEZED_BAR
        .replace("FORMULATION", formulation)
        .replace(
            "failure = { model = \"max-plastic-strain\", limit = 0.01 }",
            failure,
        )
        .replace("[[-0.02]]", &format!("[[{rate}]]"));
    for (k, x) in [0.005, 0.015, 0.025, 0.975, 0.985, 0.995]
        .iter()
        .enumerate()
    {
        text += &format!(
            "\n[[boundary]]\nname = \"held{k}\"\nbody = \"bar\"\nat = [{x}]\nvelocity = [{}]\n",
            rate * x
        );
    }
    let scene = parse_scene(&text, "bar.toml").unwrap();
    let record = run_scene(&scene, &mut |_, _| {}).unwrap();
    assert!(record.failure.is_none(), "{:?}", record.failure);
    let samples = &record.diagnostics;
    let e0 = samples[0].total_energy();
    let jump =
        |pair: &[Diagnostics]| ((pair[1].total_energy() - pair[0].total_energy()) / e0).abs();
    let removal_step = |pair: &[Diagnostics]| pair[1].failed_particles > pair[0].failed_particles;
    let first_removal = samples
        .windows(2)
        .position(removal_step)
        .expect("a removal step");
    RemovalEnergy {
        before_failure: samples
            .windows(2)
            .take(first_removal)
            .map(jump)
            .fold(0.0, f64::max),
        removal: samples
            .windows(2)
            .filter(|p| removal_step(p))
            .map(jump)
            .fold(0.0, f64::max),
        end: ((samples.last().unwrap().total_energy() - e0) / e0).abs(),
        largest: samples
            .iter()
            .map(|d| ((d.total_energy() - e0) / e0).abs())
            .fold(0.0, f64::max),
        failed: samples.last().unwrap().failed_particles,
    }
}

#[test]
fn removal_steps_keep_the_energy_balance() {
    // The forces at t^n act without the particles failing at t^n and through their
    // neighbours' rebuilt gradients (TLSPH) or pair lists (conventional SPH), so the energy
    // increments of that step must pair the stresses with the same sums (numerics.md §9.3).
    let failure = "failure = { model = \"max-plastic-strain\", limit = 0.01 }";
    for formulation in ["total-lagrangian-corrected", "updated-lagrangian"] {
        let RemovalEnergy {
            before_failure,
            removal,
            end,
            failed,
            ..
        } = removal_energy(formulation, failure, -0.02);
        assert!(failed >= 90, "{formulation}: {failed} failed");
        // Both formulations close the homogeneous squeeze to round-off before the failures
        // (measured: TLSPH 6.5e-11; conventional SPH 4.6e-11, and 1.3e-6 when its internal
        // energy was integrated as σ:D/ρ rather than from its pair sums).
        assert!(
            before_failure < 1e-9,
            "{formulation}: an ordinary step moved the total by {before_failure:.2e} of E0"
        );
        if formulation == "total-lagrangian-corrected" {
            // 94 particles fail in one step and the survivors are held: the removal step
            // closes to round-off as well (measured 3e-11; 6.1e-3 before the removal step was
            // booked).
            assert!(
                removal < 1e-9,
                "{formulation}: the removal step moved the total by {removal:.2e} of E0"
            );
        } else {
            // Conventional SPH fails the bar over five steps, and the free survivors between
            // them accelerate at once: the reported total then moves by the leap-frog's
            // ⅛Δt² Σ m |a|² term at t^n (up to 4.7e-4 of E0 in a step), which telescopes (the
            // exact per-step pairing with removals is tested in tlsph-solver,
            // `each_step_changes_the_internal_energy_by_minus_the_work_of_the_pair_forces`).
            // What the removals leave is measured at the end: 7.4e-6 of E0; 6.2e-4 when the
            // energy was integrated as σ:D/ρ with the dropped pairs taken back.
            assert!(
                end < 5e-5,
                "{formulation}: the total ended {end:.2e} of E0 off"
            );
        }
    }
}

#[test]
fn a_softening_plastic_bar_keeps_the_energy_balance_through_its_failure() {
    // The same bar stretched (v = +0.02 x): it yields at ε = σ_y/2G = 0.003, softens by
    // Peerlings damage from κ0 = 0.004 and fails at κc = 0.015 (numerics.md §9.1 on the
    // elastic–plastic stress). Softening localises: 40 of the 100 particles fail with TLSPH,
    // 32 with conventional SPH (measured; a homogeneous failure would take 94), and the rest
    // flies apart.
    // The damaged stress does the work and is booked in e, and the failed particles' e goes
    // to `deleted_particles`, so the total must stay put. Measured largest offset over the
    // run: 5.7e-5 of E0 (TLSPH), 3.8e-5 (conventional SPH), the leap-frog's ⅛Δt² Σ m|a|² once
    // the band accelerates the halves; booking e with the undamaged stress instead moved it
    // by 0.43.
    let damage = "damage = { model = \"peerlings\", kappa0 = 0.004, kappa_c = 0.015 }";
    for formulation in ["total-lagrangian-corrected", "updated-lagrangian"] {
        let RemovalEnergy {
            largest, failed, ..
        } = removal_energy(formulation, damage, 0.02);
        assert!(
            (10..100).contains(&failed),
            "{formulation}: {failed} failed (softening localises)"
        );
        assert!(
            largest < 2e-4,
            "{formulation}: the total moved by {largest:.2e} of E0"
        );
    }
}

#[test]
fn a_softening_plastic_bar_with_a_failure_criterion_keeps_the_energy_balance() {
    // The softening bar above with a maximum-plastic-strain criterion as well: a particle
    // fails by whichever comes first. With the limit 0.005 the criterion fails the band
    // before the softening has localised it: 86 particles fail with TLSPH, 78 with
    // conventional SPH (measured), against 40 and 32 by the damage law alone. The particles
    // the criterion fails leave the sums like any failed particle, so the total stays put as
    // with one mechanism (measured largest offset 6.6e-5 and 6.3e-5 of E0).
    let damage = "damage = { model = \"peerlings\", kappa0 = 0.004, kappa_c = 0.015 }";
    let both = format!("{damage}\nfailure = {{ model = \"max-plastic-strain\", limit = 0.005 }}");
    for formulation in ["total-lagrangian-corrected", "updated-lagrangian"] {
        let by_damage = removal_energy(formulation, damage, 0.02).failed;
        let RemovalEnergy {
            largest, failed, ..
        } = removal_energy(formulation, &both, 0.02);
        assert!(
            failed > by_damage + 20 && failed < 100,
            "{formulation}: {failed} failed, {by_damage} by the damage law alone"
        );
        assert!(
            largest < 2e-4,
            "{formulation}: the total moved by {largest:.2e} of E0"
        );
    }
}

#[test]
fn reference_update_and_xsph_with_a_failure_model_are_refused_at_their_line() {
    for (extra, field, needle) in [
        (
            "\n[reference_update]\nstrain_threshold = 0.1\n",
            "reference_update",
            "strain_threshold",
        ),
        ("\n[xsph]\nepsilon = 0.1\n", "xsph", "epsilon"),
    ] {
        let text = format!("{SPHERE_ON_PLATE}{extra}");
        let e = error_of(&text);
        assert_eq!(e.field, field, "{e}");
        assert_eq!(e.line, Some(line_of(&text, needle)), "{e}");
        let message = e.to_string();
        assert!(
            message.contains("`aluminium`") && message.contains("`plate`"),
            "{message}"
        );
    }
}
