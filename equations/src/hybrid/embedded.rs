//! A reduced model run in the full 12-state layout.
//!
//! The hybrid driver, its guards, transition maps and projection all index the shared layout
//! ([`crate::modes::layout`]), and that is where their correctness lives; writing them a second
//! time for 8 states would be a near-copy of the whole driver. A pruned variant
//! (`rolling::pruned`, ...) is instead *embedded*: [`Embedded`] gathers the states the variant
//! keeps from the 12-vector, calls the variant, and scatters its derivatives back. The states
//! it drops (`X`, `Y`, `Z`, `φ` for the disk) get a zero derivative, so they are **frozen**:
//! they keep their initial values (the projection at a switch may rewrite `Z`), carry no
//! integration error, and are never a result. Whoever reports from such a run must leave them
//! out; [`Embedding::frozen`] names them. In the disk driver that means: the height residual
//! `Z − a sin θ` (and so the constraint drift it contributes to) and the energy (`m g Z`) of
//! a pruned run are meaningless; the projection writes `Z` from θ at switches, which feeds
//! nothing back, since no kept derivative reads a dropped state.
//!
//! A pruned run is not bitwise the full run: the frozen states add zero to the error norm
//! (still divided by 12), so the step-size control sees only the kept states and takes
//! slightly different steps. Decisions and θ, N agree to the integration accuracy (tested at
//! `rtol = 1e-10`: transition times to 1e-9 s).
//!
//! The map is built by state name, from the constant name lists the macro emits
//! (`rolling::STATE_NAMES`, `rolling::pruned::STATE_NAMES`), and checked: [`slots`] returns an
//! [`EmbedError`] naming a variant state the layout lacks, and for the three disk variants it
//! runs at compile time ([`Variant::SLOTS`]), so such a mismatch fails the build instead of a
//! run. Constant slots matter for speed: with the map read from memory at run time, gathering
//! and scattering cost 15–30 ns per evaluation (bounds checks, no unrolling), as much as
//! pruning saves; with constant slots they compile to a few register moves.
//!
//! ```
//! use equations::Embedded;
//! use equations::models::rolling;
//! use model_runtime::Model;
//!
//! let pruned = Embedded::new(rolling::pruned::Model::default());
//! let frozen: Vec<_> = pruned.embedding().frozen_names().collect();
//! assert_eq!(frozen, ["X", "Y", "Z", "phi"]);
//!
//! let mut y = [0.0; 12];
//! y[rolling::state::theta] = 0.5;
//! y[rolling::state::Omega_x] = 1.0;
//! y[rolling::state::V_X] = 0.3;
//! let (mut full, mut embedded) = ([0.0; 12], [0.0; 12]);
//! rolling::Model::default().rhs(0.0, &y, &mut full)?;
//! pruned.rhs(0.0, &y, &mut embedded)?;
//! assert_eq!(full[rolling::state::X], 0.3); // der(X) = V_X
//! assert_eq!(embedded[rolling::state::X], 0.0); // frozen
//! let i = rolling::state::Omega_y;
//! assert!((embedded[i] - full[i]).abs() <= 1e-12 * full[i].abs());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use crate::modes::DIM;
use model_runtime::{EvalError, Model, ModelInfo};

/// Why a reduced model's states cannot be placed in a layout.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum EmbedError {
    /// A state of the reduced model is not a state of the layout.
    #[error("state `{state}` of the reduced model is not a state of the layout")]
    MissingState {
        /// The state that has no place.
        state: &'static str,
    },
    /// Two states of the reduced model carry the same name.
    #[error("the reduced model names two states `{state}`")]
    DuplicateState {
        /// The repeated name.
        state: &'static str,
    },
}

/// `a == b`, usable in constants.
const fn same(a: &str, b: &str) -> bool {
    let (a, b) = (a.as_bytes(), b.as_bytes());
    if a.len() != b.len() {
        return false;
    }
    let mut i = 0;
    while i < a.len() {
        if a[i] != b[i] {
            return false;
        }
        i += 1;
    }
    true
}

/// The layout index of each of the `K` states named `reduced` among the states named `layout`,
/// matched by name. A `const fn`, so a constant map is checked when the crate compiles.
pub const fn slots<const K: usize>(
    layout: &[&'static str; DIM],
    reduced: &[&'static str; K],
) -> Result<[usize; K], EmbedError> {
    let mut out = [0; K];
    let mut k = 0;
    while k < K {
        let state = reduced[k];
        let mut j = 0;
        while j < k {
            if same(reduced[j], state) {
                return Err(EmbedError::DuplicateState { state });
            }
            j += 1;
        }
        let mut i = 0;
        while i < DIM && !same(layout[i], state) {
            i += 1;
        }
        if i == DIM {
            return Err(EmbedError::MissingState { state });
        }
        out[k] = i;
        k += 1;
    }
    Ok(out)
}

/// Where each of the `K` states of a reduced model sits in the 12-state layout.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Embedding<const K: usize> {
    /// Layout index of each reduced state, in the reduced model's order.
    slots: [usize; K],
    /// The layout's state names.
    layout: &'static [&'static str; DIM],
}

impl<const K: usize> Embedding<K> {
    /// Matches the states named `reduced` to those named `layout`.
    pub fn new(
        layout: &'static [&'static str; DIM],
        reduced: &[&'static str; K],
    ) -> Result<Self, EmbedError> {
        Ok(Embedding {
            slots: slots(layout, reduced)?,
            layout,
        })
    }

    /// The layout index of each reduced state.
    pub fn slots(&self) -> &[usize; K] {
        &self.slots
    }

    /// Whether the reduced model integrates layout state `index`.
    pub fn keeps(&self, index: usize) -> bool {
        self.slots.contains(&index)
    }

    /// The layout indices the reduced model does not integrate, in layout order.
    pub fn frozen(&self) -> impl Iterator<Item = usize> + '_ {
        (0..DIM).filter(|&i| !self.keeps(i))
    }

    /// The names of the frozen states, in layout order.
    pub fn frozen_names(&self) -> impl Iterator<Item = &'static str> + '_ {
        let names = self.layout;
        self.frozen().map(move |i| names[i])
    }
}

/// A reduced model with a fixed place in the 12-state layout of its full model.
pub trait Variant<const K: usize>: Model<K> {
    /// The full model's state names, in index order.
    const LAYOUT: &'static [&'static str; DIM];
    /// The layout index of each state, from `slots` (this module) at compile time.
    const SLOTS: [usize; K];
}

/// `Variant` for the pruned variant of a generated model, its slots checked at compile time.
macro_rules! pruned_variant {
    ($full:ident) => {
        impl Variant<{ crate::models::$full::pruned::N_STATES }>
            for crate::models::$full::pruned::Model
        {
            const LAYOUT: &'static [&'static str; DIM] = &crate::models::$full::STATE_NAMES;
            const SLOTS: [usize; crate::models::$full::pruned::N_STATES] =
                match slots(Self::LAYOUT, &crate::models::$full::pruned::STATE_NAMES) {
                    Ok(s) => s,
                    Err(_) => panic!(concat!(
                        "`",
                        stringify!($full),
                        "::pruned` has a state that `",
                        stringify!($full),
                        "` lacks"
                    )),
                };
        }
    };
}

pruned_variant!(rolling);
pruned_variant!(sliding);
pruned_variant!(sliding_cartesian);

/// A `K`-state model seen as a 12-state one: the states it drops are frozen (zero derivative).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Embedded<M, const K: usize> {
    model: M,
}

impl<M: Variant<K>, const K: usize> Embedded<M, K> {
    /// Embeds `model` into the state layout of its full model.
    pub fn new(model: M) -> Self {
        Embedded { model }
    }

    /// Where the model's states sit, and which layout states are frozen.
    pub fn embedding(&self) -> Embedding<K> {
        Embedding {
            slots: M::SLOTS,
            layout: M::LAYOUT,
        }
    }

    /// The reduced model itself.
    pub fn model(&self) -> &M {
        &self.model
    }

    /// The kept states of a layout vector, in the reduced model's order.
    #[inline(always)]
    fn gather(y: &[f64; DIM]) -> [f64; K] {
        std::array::from_fn(|i| y[M::SLOTS[i]])
    }

    /// A layout vector holding `z` in the kept slots and zero in the frozen ones.
    #[inline(always)]
    fn scatter(z: &[f64; K]) -> [f64; DIM] {
        let mut y = [0.0; DIM];
        for (&slot, &v) in M::SLOTS.iter().zip(z) {
            y[slot] = v;
        }
        y
    }
}

impl<M: Variant<K>, const K: usize> Model<DIM> for Embedded<M, K> {
    /// The reduced model's description (its name, its `K` state names and its op counts):
    /// the model that actually computes; the layout states it does not name are frozen.
    fn info(&self) -> &'static ModelInfo {
        self.model.info()
    }

    #[inline]
    fn rhs(&self, t: f64, y: &[f64; DIM], dy: &mut [f64; DIM]) -> Result<(), EvalError> {
        let mut dz = [0.0; K];
        self.model.rhs(t, &Self::gather(y), &mut dz)?;
        *dy = Self::scatter(&dz);
        Ok(())
    }

    fn jacobian(
        &self,
        t: f64,
        y: &[f64; DIM],
        jac: &mut [[f64; DIM]; DIM],
    ) -> Result<(), EvalError> {
        let mut reduced = [[0.0; K]; K];
        self.model.jacobian(t, &Self::gather(y), &mut reduced)?;
        *jac = [[0.0; DIM]; DIM];
        for (row, &i) in reduced.iter().zip(&M::SLOTS) {
            jac[i] = Self::scatter(row);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::{rolling, sliding, sliding_cartesian};

    fn state() -> [f64; DIM] {
        [
            0.1, -0.2, 0.02, 0.3, -0.4, 0.05, 0.7, 0.6, 1.1, 2.0, -3.0, 5.0,
        ]
    }

    #[test]
    fn kept_derivatives_are_the_variants_and_frozen_ones_zero() {
        let embedded = Embedded::new(rolling::pruned::Model::default());
        let y = state();
        let mut dy = [f64::NAN; DIM];
        embedded.rhs(0.0, &y, &mut dy).unwrap();
        let z: [f64; rolling::pruned::N_STATES] = std::array::from_fn(|i| {
            y[rolling::STATE_NAMES
                .iter()
                .position(|n| *n == rolling::pruned::STATE_NAMES[i])
                .unwrap()]
        });
        let mut dz = [0.0; rolling::pruned::N_STATES];
        rolling::pruned::Model::default()
            .rhs(0.0, &z, &mut dz)
            .unwrap();
        for (k, name) in rolling::pruned::STATE_NAMES.iter().enumerate() {
            let i = rolling::STATE_NAMES.iter().position(|n| n == name).unwrap();
            assert_eq!(dy[i], dz[k], "{name}");
        }
        for i in [rolling::state::X, rolling::state::Y, rolling::state::Z] {
            assert_eq!(dy[i], 0.0);
        }
        assert_eq!(dy[rolling::state::phi], 0.0);
    }

    #[test]
    fn jacobian_is_the_variants_in_the_kept_slots_and_zero_elsewhere() {
        let model = sliding_cartesian::pruned::Model::default();
        let embedded = Embedded::new(model.clone());
        let mut y = state();
        y[sliding_cartesian::state::u_X] = 1e-3;
        let mut jac = [[f64::NAN; DIM]; DIM];
        embedded.jacobian(0.0, &y, &mut jac).unwrap();
        let slots = embedded.embedding().slots().to_owned();
        let z = slots.map(|i| y[i]);
        let mut reduced = [[0.0; sliding_cartesian::pruned::N_STATES]; 8];
        model.jacobian(0.0, &z, &mut reduced).unwrap();
        for (i, row) in jac.iter().enumerate() {
            for (j, &entry) in row.iter().enumerate() {
                let expected = match (
                    slots.iter().position(|&s| s == i),
                    slots.iter().position(|&s| s == j),
                ) {
                    (Some(a), Some(b)) => reduced[a][b],
                    _ => 0.0,
                };
                assert_eq!(entry, expected, "d der({i}) / d y{j}");
            }
        }
        let theta = sliding_cartesian::state::theta;
        let omega_y = sliding_cartesian::state::Omega_y;
        assert_eq!(jac[theta][omega_y], 1.0, "der(theta) = Omega_y");
    }

    #[test]
    fn a_state_the_layout_lacks_is_named() {
        // The rolling variant carries V_X, which the polar sliding layout replaces by v_C.
        let err = Embedding::new(&sliding::STATE_NAMES, &rolling::pruned::STATE_NAMES).unwrap_err();
        assert_eq!(err, EmbedError::MissingState { state: "V_X" });
        assert!(err.to_string().contains("`V_X`"), "{err}");
        let twice = ["theta", "psi", "theta"];
        assert_eq!(
            slots(&rolling::STATE_NAMES, &twice),
            Err(EmbedError::DuplicateState { state: "theta" })
        );
    }

    #[test]
    fn constant_slots_are_the_named_ones() {
        let runtime = Embedding::new(&rolling::STATE_NAMES, &rolling::pruned::STATE_NAMES).unwrap();
        let embedded = Embedded::new(rolling::pruned::Model::default());
        assert_eq!(runtime, embedded.embedding());
        for (k, &i) in runtime.slots().iter().enumerate() {
            assert_eq!(rolling::STATE_NAMES[i], rolling::pruned::STATE_NAMES[k]);
        }
        let polar = Embedded::new(sliding::pruned::Model::default());
        let names: Vec<_> = polar.embedding().frozen_names().collect();
        assert_eq!(names, ["X", "Y", "Z", "phi"]);
    }
}
