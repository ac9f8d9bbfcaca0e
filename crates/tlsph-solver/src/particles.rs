//! Particle state as structure of arrays. Only state every TLSPH run needs lives here;
//! optional effects own their state elsewhere.

use tlsph_math::{Tensor, Tensor3, Vector};

/// Per-particle state, indexed globally (bodies are contiguous ranges).
#[derive(Debug, Clone)]
pub(crate) struct Particles<const D: usize> {
    /// Reference positions X.
    pub positions0: Vec<Vector<D>>,
    /// Displacements u^n = x^n − X.
    pub displacements: Vec<Vector<D>>,
    /// Staggered velocities v^{n+½} (after a step) — see `Simulation::velocity`.
    pub velocities: Vec<Vector<D>>,
    /// Accelerations a^n of the last step.
    pub accelerations: Vec<Vector<D>>,
    /// Masses m = ρ0 V0.
    pub masses: Vec<f64>,
    /// Reference volumes V0.
    pub volumes0: Vec<f64>,
    /// Cauchy stress σ^n (3x3; plane strain / uniaxial strain components included).
    pub stress: Vec<Tensor3>,
    /// First Piola–Kirchhoff stress P^n, `D`x`D` block.
    pub pk1: Vec<Tensor<D>>,
    /// Deformation gradient F^n.
    pub deformation_gradient: Vec<Tensor<D>>,
    /// Material velocity gradient Ḟ^{n−½} (scratch of the current step, kept for output).
    pub deformation_rate: Vec<Tensor<D>>,
    /// det F^n.
    pub jacobian: Vec<f64>,
    /// Specific internal energy e^n [J/kg].
    pub internal_energy: Vec<f64>,
}

impl<const D: usize> Particles<D> {
    pub fn with_capacity(n: usize) -> Self {
        Self {
            positions0: Vec::with_capacity(n),
            displacements: Vec::with_capacity(n),
            velocities: Vec::with_capacity(n),
            accelerations: Vec::with_capacity(n),
            masses: Vec::with_capacity(n),
            volumes0: Vec::with_capacity(n),
            stress: Vec::with_capacity(n),
            pk1: Vec::with_capacity(n),
            deformation_gradient: Vec::with_capacity(n),
            deformation_rate: Vec::with_capacity(n),
            jacobian: Vec::with_capacity(n),
            internal_energy: Vec::with_capacity(n),
        }
    }

    /// Appends one particle at rest in the reference configuration.
    pub fn push(&mut self, position0: Vector<D>, volume0: f64, density0: f64, velocity: Vector<D>) {
        self.positions0.push(position0);
        self.displacements.push(Vector::zeros());
        self.velocities.push(velocity);
        self.accelerations.push(Vector::zeros());
        self.masses.push(density0 * volume0);
        self.volumes0.push(volume0);
        self.stress.push(Tensor3::zeros());
        self.pk1.push(Tensor::zeros());
        self.deformation_gradient.push(Tensor::identity());
        self.deformation_rate.push(Tensor::zeros());
        self.jacobian.push(1.0);
        self.internal_energy.push(0.0);
    }

    /// Drops every particle from index `n` on (the symmetry ghosts, before they are rebuilt).
    pub fn truncate(&mut self, n: usize) {
        self.positions0.truncate(n);
        self.displacements.truncate(n);
        self.velocities.truncate(n);
        self.accelerations.truncate(n);
        self.masses.truncate(n);
        self.volumes0.truncate(n);
        self.stress.truncate(n);
        self.pk1.truncate(n);
        self.deformation_gradient.truncate(n);
        self.deformation_rate.truncate(n);
        self.jacobian.truncate(n);
        self.internal_energy.truncate(n);
    }

    pub fn len(&self) -> usize {
        self.positions0.len()
    }
}
