//! The `[[material]]` tables: which keys each model takes, and their conversion into solver
//! material models with every parameter checked and located (numerics.md §8).

use crate::scene::{Context, SceneError};
use crate::scene_file::{DamageTable, EosTable, FailureTable, MaterialTable};
use std::ops::Range;
use tlsph_materials::eos::MieGruneisenParameters;
use tlsph_materials::strength::JohnsonCookStrengthParameters;
use tlsph_materials::{
    EquationOfState, GradyKipp, JohnsonCookFailure, JohnsonCookStrength, LinearElastic, LinearEos,
    MaterialError, MaxPlasticStrainFailure, MaxStressFailure, MieGruneisen, PeerlingsSoftening,
    PolynomialEos, VonMisesPlasticity,
};
use tlsph_solver::{
    DamageModel, ElasticDamage, ElasticPlastic, FailureModel, MaterialModel, PressureModel,
    StrengthModel, Thermal,
};
use toml::Spanned;

/// Material models and the keys each accepts beyond `name`, `model` and `density`.
const MODELS: [(&str, &[&str]); 3] = [
    (
        "linear-elastic",
        &["youngs_modulus", "poisson_ratio", "damage"],
    ),
    (
        "elastic-plastic",
        &[
            "youngs_modulus",
            "poisson_ratio",
            "yield_stress",
            "tangent_modulus",
            "plastic_modulus",
            "specific_heat",
            "room_temperature",
            "min_pressure",
            "eos",
            "failure",
            "damage",
        ],
    ),
    (
        "johnson-cook",
        &[
            "youngs_modulus",
            "poisson_ratio",
            "a",
            "b",
            "n",
            "c",
            "m",
            "reference_strain_rate",
            "room_temperature",
            "melt_temperature",
            "accurate_iteration",
            "specific_heat",
            "min_pressure",
            "eos",
            "failure",
            "damage",
        ],
    ),
];

/// Every optional key of a material table with its span, for "not a parameter of" checks.
fn given_keys(m: &MaterialTable) -> Vec<(&'static str, Range<usize>)> {
    let mut keys = Vec::new();
    let mut push = |name: &'static str, span: Option<Range<usize>>| {
        if let Some(span) = span {
            keys.push((name, span));
        }
    };
    let f = |v: &Option<Spanned<f64>>| v.as_ref().map(|x| x.span());
    push("youngs_modulus", f(&m.youngs_modulus));
    push("poisson_ratio", f(&m.poisson_ratio));
    push("yield_stress", f(&m.yield_stress));
    push("tangent_modulus", f(&m.tangent_modulus));
    push("plastic_modulus", f(&m.plastic_modulus));
    push("a", f(&m.a));
    push("b", f(&m.b));
    push("n", f(&m.n));
    push("c", f(&m.c));
    push("m", f(&m.m));
    push("reference_strain_rate", f(&m.reference_strain_rate));
    push("melt_temperature", f(&m.melt_temperature));
    push(
        "accurate_iteration",
        m.accurate_iteration.as_ref().map(|x| x.span()),
    );
    push("room_temperature", f(&m.room_temperature));
    push("specific_heat", f(&m.specific_heat));
    push("min_pressure", f(&m.min_pressure));
    push("eos", m.eos.as_ref().map(|x| x.span()));
    push("failure", m.failure.as_ref().map(|x| x.span()));
    push("damage", m.damage.as_ref().map(|x| x.span()));
    keys
}

/// Converts one `[[material]]` table into a solver material model.
pub(crate) fn material_model(
    ctx: &Context<'_>,
    m: &MaterialTable,
    field: &dyn Fn(&str) -> String,
) -> Result<MaterialModel, SceneError> {
    let model_name = m.model.get_ref().as_str();
    let Some((_, allowed)) = MODELS.iter().find(|(name, _)| *name == model_name) else {
        let names: Vec<&str> = MODELS.iter().map(|(n, _)| *n).collect();
        return Err(ctx.error(
            &m.model.span(),
            &field("model"),
            format!(
                "unknown material model `{model_name}`; available: {}",
                names.join(", ")
            ),
        ));
    };
    for (key, span) in given_keys(m) {
        if !allowed.contains(&key) {
            return Err(ctx.error(
                &span,
                &field(key),
                format!(
                    "is not a parameter of model `{model_name}` (its keys: {})",
                    allowed.join(", ")
                ),
            ));
        }
    }
    let need = |v: &Option<Spanned<f64>>, key: &str| -> Result<(f64, Range<usize>), SceneError> {
        v.as_ref().map(|x| (*x.get_ref(), x.span())).ok_or_else(|| {
            ctx.error(
                &m.model.span(),
                &field(key),
                format!("is required by model `{model_name}`"),
            )
        })
    };
    // Locates a MaterialError at the key it names (falls back to the model line).
    let locate = |err: MaterialError| {
        let span = given_keys(m)
            .into_iter()
            .find(|(k, _)| *k == err.parameter)
            .map_or(m.model.span(), |(_, s)| s);
        ctx.error(
            &span,
            &field(err.parameter),
            format!("{} is not allowed: must be {}", err.value, err.expected),
        )
    };
    let e = need(&m.youngs_modulus, "youngs_modulus")?;
    let nu = need(&m.poisson_ratio, "poisson_ratio")?;
    let elastic = LinearElastic::new(e.0, nu.0).map_err(locate)?;
    if model_name == "linear-elastic" {
        return Ok(match &m.damage {
            None => MaterialModel::LinearElastic(elastic),
            Some(t) => MaterialModel::ElasticDamage(ElasticDamage {
                elastic,
                damage: damage(ctx, t, field)?,
            }),
        });
    }
    let optional = |v: &Option<Spanned<f64>>| v.as_ref().map(|x| *x.get_ref());
    let strength = if model_name == "elastic-plastic" {
        let yield_stress = need(&m.yield_stress, "yield_stress")?.0;
        let vm = match (&m.tangent_modulus, &m.plastic_modulus) {
            (Some(t), None) => {
                VonMisesPlasticity::from_tangent_modulus(yield_stress, e.0, *t.get_ref())
            }
            (None, Some(p)) => VonMisesPlasticity::new(yield_stress, *p.get_ref()),
            (None, None) => VonMisesPlasticity::new(yield_stress, 0.0),
            (Some(t), Some(_)) => {
                return Err(ctx.error(
                    &t.span(),
                    &field("tangent_modulus"),
                    "give tangent_modulus or plastic_modulus, not both".into(),
                ))
            }
        }
        .map_err(locate)?;
        StrengthModel::VonMises(vm)
    } else {
        let parameters = JohnsonCookStrengthParameters {
            a: need(&m.a, "a")?.0,
            b: need(&m.b, "b")?.0,
            n: need(&m.n, "n")?.0,
            c: need(&m.c, "c")?.0,
            m: need(&m.m, "m")?.0,
            reference_strain_rate: need(&m.reference_strain_rate, "reference_strain_rate")?.0,
            room_temperature: need(&m.room_temperature, "room_temperature")?.0,
            melt_temperature: need(&m.melt_temperature, "melt_temperature")?.0,
        };
        StrengthModel::JohnsonCook {
            model: JohnsonCookStrength::new(parameters).map_err(locate)?,
            iterate: m.accurate_iteration.as_ref().is_none_or(|x| *x.get_ref()),
        }
    };
    let thermal = match &m.specific_heat {
        None => {
            // For von Mises materials room_temperature only sets the heating's start value.
            if let (Some(t), "elastic-plastic") = (&m.room_temperature, model_name) {
                return Err(ctx.error(
                    &t.span(),
                    &field("room_temperature"),
                    "has no effect without specific_heat (adiabatic heating); give both or neither"
                        .into(),
                ));
            }
            None
        }
        Some(cv) => {
            let specific_heat = ctx.positive(cv, &field("specific_heat"))?;
            let room_temperature = match &m.room_temperature {
                Some(t) => {
                    let value = *t.get_ref();
                    if !(value.is_finite() && value >= 0.0) {
                        return Err(ctx.error(
                            &t.span(),
                            &field("room_temperature"),
                            format!("must be ≥ 0 K, got {value}"),
                        ));
                    }
                    value
                }
                None => {
                    return Err(ctx.error(
                        &cv.span(),
                        &field("room_temperature"),
                        "is required with specific_heat (initial temperature)".into(),
                    ))
                }
            };
            Some(Thermal {
                specific_heat,
                room_temperature,
            })
        }
    };
    let min_pressure = match optional(&m.min_pressure) {
        // A cutoff limits tension (negative pressure): a positive value would hold every
        // particle in compression.
        Some(p) if !(p.is_finite() && p <= 0.0) => {
            return Err(ctx.error(
                &m.min_pressure.as_ref().map_or(m.model.span(), |x| x.span()),
                &field("min_pressure"),
                format!("must be a finite pressure ≤ 0 (tension is negative), got {p}"),
            ))
        }
        other => other,
    };
    let pressure = match &m.eos {
        None => PressureModel::Hypoelastic,
        Some(t) => PressureModel::Eos(eos(ctx, t, field, e.0.max(0.0), m)?),
    };
    let failure = match &m.failure {
        None => None,
        Some(t) => Some(failure(ctx, t, field, &strength)?),
    };
    // With both, the particle fails by whichever comes first (docs/scene-format.md, "Damage on
    // plastic materials").
    let damage = match &m.damage {
        None => None,
        Some(t) => Some(damage(ctx, t, field)?),
    };
    Ok(MaterialModel::ElasticPlastic(ElasticPlastic {
        elastic,
        strength,
        pressure,
        min_pressure,
        thermal,
        failure,
        damage,
    }))
}

/// `failure = { model = "johnson-cook", d = [D1..D5] }` (rate and temperature references from
/// the Johnson–Cook strength, or given in the table), `{ model = "max-plastic-strain", limit }`
/// or `{ model = "max-principal-stress", limit }` (numerics.md §8.6, §8.9, §9.3).
fn failure(
    ctx: &Context<'_>,
    t: &Spanned<FailureTable>,
    field: &dyn Fn(&str) -> String,
    strength: &StrengthModel,
) -> Result<FailureModel, SceneError> {
    let span = t.span();
    let f = t.get_ref();
    let err =
        |key: &str, message: String| ctx.error(&span, &field(&format!("failure.{key}")), message);
    let locate = |e: MaterialError| {
        err(
            e.parameter,
            format!("{} is not allowed: must be {}", e.value, e.expected),
        )
    };
    // The limit models name their parameter after the quantity; the scene's key is `limit`.
    let locate_limit = |e: MaterialError| {
        locate(MaterialError {
            parameter: "limit",
            ..e
        })
    };
    let only = |allowed: &[&str]| -> Result<(), SceneError> {
        let given = [
            ("d", f.d.is_some()),
            ("limit", f.limit.is_some()),
            ("reference_strain_rate", f.reference_strain_rate.is_some()),
            ("room_temperature", f.room_temperature.is_some()),
            ("melt_temperature", f.melt_temperature.is_some()),
        ];
        for (key, present) in given {
            if present && !allowed.contains(&key) {
                return Err(err(
                    key,
                    format!("is not a parameter of failure model `{}`", f.model),
                ));
            }
        }
        Ok(())
    };
    match f.model.as_str() {
        "johnson-cook" => {
            only(&["d", "reference_strain_rate", "room_temperature", "melt_temperature"])?;
            let d = f.d.as_ref().ok_or_else(|| err("d", "is required: [D1, D2, D3, D4, D5]".into()))?;
            if d.len() != 5 {
                return Err(err("d", format!("needs 5 values D1..D5, got {}", d.len())));
            }
            let model = JohnsonCookFailure::new(d[0], d[1], d[2], d[3], d[4]).map_err(locate)?;
            // ε̇0, T_room, T_melt: from the Johnson–Cook strength unless given here.
            let from_strength = match strength {
                StrengthModel::JohnsonCook { model, .. } => {
                    let p = model.parameters();
                    Some((p.reference_strain_rate, p.room_temperature, p.melt_temperature))
                }
                StrengthModel::VonMises(_) => None,
            };
            let pick = |given: Option<f64>, index: usize, key: &str| -> Result<f64, SceneError> {
                given
                    .or(from_strength.map(|t| [t.0, t.1, t.2][index]))
                    .ok_or_else(|| err(key, "is required (the strength model does not provide it)".into()))
            };
            let reference_strain_rate = pick(f.reference_strain_rate, 0, "reference_strain_rate")?;
            let room_temperature = pick(f.room_temperature, 1, "room_temperature")?;
            let melt_temperature = pick(f.melt_temperature, 2, "melt_temperature")?;
            if !(reference_strain_rate.is_finite() && reference_strain_rate > 0.0) {
                return Err(err("reference_strain_rate", format!("must be > 0, got {reference_strain_rate}")));
            }
            if melt_temperature.is_nan() || melt_temperature <= room_temperature {
                return Err(err("melt_temperature", format!("must exceed room_temperature ({room_temperature}), got {melt_temperature}")));
            }
            Ok(FailureModel::JohnsonCook {
                model,
                reference_strain_rate,
                room_temperature,
                melt_temperature,
            })
        }
        "max-plastic-strain" => {
            only(&["limit"])?;
            let limit = f.limit.ok_or_else(|| err("limit", "is required".into()))?;
            Ok(FailureModel::MaxPlasticStrain(MaxPlasticStrainFailure::new(limit).map_err(locate_limit)?))
        }
        "max-principal-stress" => {
            only(&["limit"])?;
            let limit = f.limit.ok_or_else(|| err("limit", "is required".into()))?;
            Ok(FailureModel::MaxPrincipalStress(MaxStressFailure::new(limit).map_err(locate_limit)?))
        }
        other => Err(err(
            "model",
            format!("unknown failure model `{other}`; available: johnson-cook, max-plastic-strain, max-principal-stress"),
        )),
    }
}

/// Flaw seed of Grady–Kipp when a scene gives none (numerics.md §9.2: fixed seed; documented
/// in docs/scene-format.md).
pub const DEFAULT_FLAW_SEED: u64 = 1;

/// `damage = { model = "peerlings", kappa0, kappa_c }` or
/// `{ model = "grady-kipp", m, k, seed }` of a linear-elastic material (numerics.md §9.1–9.2).
fn damage(
    ctx: &Context<'_>,
    t: &Spanned<DamageTable>,
    field: &dyn Fn(&str) -> String,
) -> Result<DamageModel, SceneError> {
    let span = t.span();
    let d = t.get_ref();
    let err =
        |key: &str, message: String| ctx.error(&span, &field(&format!("damage.{key}")), message);
    let locate = |e: MaterialError| {
        err(
            e.parameter,
            format!("{} is not allowed: must be {}", e.value, e.expected),
        )
    };
    let only = |allowed: &[&str]| -> Result<(), SceneError> {
        let given = [
            ("kappa0", d.kappa0.is_some()),
            ("kappa_c", d.kappa_c.is_some()),
            ("m", d.m.is_some()),
            ("k", d.k.is_some()),
            ("seed", d.seed.is_some()),
        ];
        for (key, present) in given {
            if present && !allowed.contains(&key) {
                return Err(err(
                    key,
                    format!(
                        "is not a parameter of damage model `{}` (its keys: {})",
                        d.model,
                        allowed.join(", ")
                    ),
                ));
            }
        }
        Ok(())
    };
    let need = |v: Option<f64>, key: &str| {
        v.ok_or_else(|| err(key, format!("is required by damage model `{}`", d.model)))
    };
    match d.model.as_str() {
        "peerlings" => {
            only(&["kappa0", "kappa_c"])?;
            let law =
                PeerlingsSoftening::new(need(d.kappa0, "kappa0")?, need(d.kappa_c, "kappa_c")?)
                    .map_err(locate)?;
            Ok(DamageModel::Peerlings(law))
        }
        "grady-kipp" => {
            only(&["m", "k", "seed"])?;
            let model = GradyKipp::new(need(d.m, "m")?, need(d.k, "k")?).map_err(locate)?;
            let seed = match d.seed {
                None => DEFAULT_FLAW_SEED,
                Some(s) => u64::try_from(s)
                    .map_err(|_| err("seed", format!("must be an integer ≥ 0, got {s}")))?,
            };
            Ok(DamageModel::GradyKipp { model, seed })
        }
        other => Err(err(
            "model",
            format!("unknown damage model `{other}`; available: peerlings, grady-kipp"),
        )),
    }
}

fn eos(
    ctx: &Context<'_>,
    t: &Spanned<EosTable>,
    field: &dyn Fn(&str) -> String,
    _youngs_modulus: f64,
    m: &MaterialTable,
) -> Result<EquationOfState, SceneError> {
    let span = t.span();
    let e = t.get_ref();
    let need = |v: Option<f64>, key: &str| {
        v.ok_or_else(|| {
            ctx.error(
                &span,
                &field(&format!("eos.{key}")),
                format!("is required by EOS model `{}`", e.model),
            )
        })
    };
    let locate = |err: MaterialError| {
        ctx.error(
            &span,
            &field(&format!("eos.{}", err.parameter)),
            format!("{} is not allowed: must be {}", err.value, err.expected),
        )
    };
    let unexpected = |keys: &[(&str, bool)]| -> Result<(), SceneError> {
        for (k, given) in keys {
            if *given {
                return Err(ctx.error(
                    &span,
                    &field(&format!("eos.{k}")),
                    format!("is not a parameter of EOS model `{}`", e.model),
                ));
            }
        }
        Ok(())
    };
    match e.model.as_str() {
        "linear" => {
            unexpected(&[
                ("coefficients", e.coefficients.is_some()),
                ("sound_speed", e.sound_speed.is_some()),
                ("s1", e.s1.is_some()),
                ("s2", e.s2.is_some()),
                ("s3", e.s3.is_some()),
                ("gamma0", e.gamma0.is_some()),
                ("a", e.a.is_some()),
            ])?;
            Ok(EquationOfState::Linear(
                LinearEos::new(need(e.bulk_modulus, "bulk_modulus")?).map_err(locate)?,
            ))
        }
        "polynomial" => {
            unexpected(&[
                ("bulk_modulus", e.bulk_modulus.is_some()),
                ("sound_speed", e.sound_speed.is_some()),
                ("s1", e.s1.is_some()),
                ("s2", e.s2.is_some()),
                ("s3", e.s3.is_some()),
                ("gamma0", e.gamma0.is_some()),
                ("a", e.a.is_some()),
            ])?;
            let c = e.coefficients.as_ref().ok_or_else(|| {
                ctx.error(
                    &span,
                    &field("eos.coefficients"),
                    "is required by EOS model `polynomial`: [C0, C1, ..., C6]".into(),
                )
            })?;
            if c.len() != 7 {
                return Err(ctx.error(
                    &span,
                    &field("eos.coefficients"),
                    format!("needs 7 values C0..C6, got {}", c.len()),
                ));
            }
            let array: [f64; 7] = std::array::from_fn(|k| c[k]);
            Ok(EquationOfState::Polynomial(
                PolynomialEos::new(array).map_err(locate)?,
            ))
        }
        "mie-gruneisen" => {
            unexpected(&[
                ("bulk_modulus", e.bulk_modulus.is_some()),
                ("coefficients", e.coefficients.is_some()),
            ])?;
            let parameters = MieGruneisenParameters {
                reference_density: *m.density.get_ref(),
                sound_speed: need(e.sound_speed, "sound_speed")?,
                s1: need(e.s1, "s1")?,
                s2: e.s2.unwrap_or(0.0),
                s3: e.s3.unwrap_or(0.0),
                gamma0: need(e.gamma0, "gamma0")?,
                a: e.a.unwrap_or(0.0),
            };
            Ok(EquationOfState::MieGruneisen(
                MieGruneisen::new(parameters).map_err(locate)?,
            ))
        }
        other => Err(ctx.error(
            &span,
            &field("eos.model"),
            format!("unknown EOS model `{other}`; available: linear, polynomial, mie-gruneisen"),
        )),
    }
}
