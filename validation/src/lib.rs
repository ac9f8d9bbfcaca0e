//! Replays of the published validation problems. Each problem module builds its scene(s),
//! runs them, compares with `reference-data/` and returns a [`ProblemReport`].
//! [`problems()`] lists them for `cargo xtask validate`; [`cost::sweep`] runs the
//! accuracy-versus-cost sweeps for `cargo xtask cost`.

pub mod analytic;
pub mod cost;
pub mod problems;
pub mod report;
pub mod stability;
pub mod variants;

pub use report::{Curve, ProblemReport, ReportRow, RunCost, Series, Tier};

/// A validation problem of the suite.
#[derive(Debug, Clone, Copy)]
pub struct Problem {
    /// Id as in `problems.md`, e.g. `R-P2`.
    pub id: &'static str,
    /// One-line title.
    pub title: &'static str,
    /// Runs it at a tier.
    pub run: fn(Tier) -> ProblemReport,
}

/// Every problem of the suite, in catalogue order.
pub fn problems() -> Vec<Problem> {
    vec![
        Problem {
            id: problems::r_p1::ID,
            title: "1D stability: symmetric impact of two elastic rods, TLSPH vs conventional SPH",
            run: problems::r_p1::run,
        },
        Problem {
            id: problems::r_p2::ID,
            title: "elastic uniaxial-strain wave, two-plate impact",
            run: problems::r_p2::run,
        },
        Problem {
            id: "R-P3",
            title: "gradient consistency, six-particle tables 6.2/6.3",
            run: |_| problems::r_p3::run(),
        },
        Problem {
            id: problems::r_p4::ID,
            title: "clamped-free rod vibration from a linear velocity field",
            run: problems::r_p4::run,
        },
        Problem {
            id: problems::r_p5::ID,
            title: "2D stability: pre-tensioned steel block, TLSPH vs conventional SPH",
            run: problems::r_p5::run,
        },
        Problem {
            id: problems::r_p6::ID,
            title: "Taylor impact of a copper rod on a rigid anvil",
            run: problems::r_p6::run,
        },
        Problem {
            id: problems::r_p9a::ID,
            title: "2D plate impact, Ti flyer on Al target at 660 m/s: TLSPH vs conventional SPH",
            run: problems::r_p9a::run,
        },
        Problem {
            id: problems::r_c7x::ID,
            title: "XSPH vs artificial viscosity, symmetric steel rod impact",
            run: problems::r_c7x::run,
        },
        Problem {
            id: problems::f_a1::ID,
            title: "plate with a central hole, quasi-static tension vs Kirsch",
            run: problems::f_a1::run,
        },
        Problem {
            id: problems::f_a12::ID,
            title: "Grady–Kipp flaw damage around a circular hole (Fuller A.12)",
            run: problems::f_a12::run,
        },
        Problem {
            id: problems::f_a13::ID,
            title: "Peerlings softening damage in a waisted bar (Fuller A.13)",
            run: problems::f_a13::run,
        },
        Problem {
            id: problems::f_a2::ID,
            title: "Fuller: elastic ball bouncing off a fixed wall through the kernel, XSPH off/on",
            run: problems::f_a2::run,
        },
        Problem {
            id: problems::f_a3::ID,
            title: "Fuller: linear momentum of colliding discs, mass-ratio and speed sweep",
            run: problems::f_a3::run,
        },
        Problem {
            id: problems::f_a4::ID,
            title: "Fuller: angular momentum of a rotating disc, conventional SPH vs TLSPH",
            run: problems::f_a4::run,
        },
        Problem {
            id: problems::f_a5::ID,
            title: "Fuller: colliding rubber rings, artificial stress off (A) and on (B)",
            run: problems::f_a5::run,
        },
        Problem {
            id: problems::f_a6::ID,
            title:
                "Fuller: elastic ball bouncing off a fixed wall with penalty contact vs the kernel",
            run: problems::f_a6::run,
        },
        Problem {
            id: "R-C3",
            title: "linear stability of TLSPH vs Eulerian SPH lattices (Reveles ch. 3)",
            run: stability::run,
        },
    ]
}
