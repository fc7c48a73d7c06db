//! The located extrema of a run (`extrema.csv`), and the numbers and figure points read off
//! them instead of off samples.
//!
//! The run locates every extremum of θ, N and the slip speed on the integrator's dense output
//! (`equations::hybrid::extrema`), so what is read here does not depend on the sampling rate.
//! θ's oscillation is told from its ripples by hysteresis: a minimum counts as a cycle
//! boundary once θ has risen [`PROMINENCE`] of the window's range above it.

use equations::{Extremum, ExtremumKind, Watched};

use crate::output::cells::{Cell, Table};

/// Header of `extrema.csv`.
pub const EXTREMA_HEADER: &str = "t_s,quantity,kind,value";

/// A θ minimum bounds a cycle when θ rises this fraction of its range (in the window
/// considered) above it before the next minimum.
pub const PROMINENCE: f64 = 0.05;

/// The name of a quantity in `extrema.csv`, with its unit.
pub fn quantity_name(q: Watched) -> &'static str {
    match q {
        Watched::Theta => "theta_rad",
        Watched::NormalForce => "N_over_mg",
        Watched::SlipSpeed => "v_C_m_per_s",
    }
}

/// The run's extrema sorted by time, with N as N/mg.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Located {
    list: Vec<Extremum>,
}

impl Located {
    /// The extrema of a run (any order), N divided by `mg`.
    pub fn new(extrema: &[Extremum], mg: f64) -> Located {
        let mut list: Vec<Extremum> = extrema
            .iter()
            .map(|e| match e.quantity {
                Watched::NormalForce => Extremum {
                    value: e.value / mg,
                    ..*e
                },
                _ => *e,
            })
            .collect();
        list.sort_by(|a, b| a.t.total_cmp(&b.t));
        Located { list }
    }

    /// Whether the run located nothing (a synthetic run, or one too short for a step).
    pub fn is_empty(&self) -> bool {
        self.list.is_empty()
    }

    /// The extrema of `q` of `kind` within `[t0, t1]`, in time order.
    pub fn of(
        &self,
        q: Watched,
        kind: ExtremumKind,
        t0: f64,
        t1: f64,
    ) -> impl Iterator<Item = &Extremum> + '_ {
        self.list
            .iter()
            .filter(move |e| e.quantity == q && e.kind == kind && e.t >= t0 && e.t <= t1)
    }

    /// Every extremum of `q` (maxima and minima) within `[t0, t1]`, in time order; at a mode
    /// switch N's value before it comes first.
    pub fn all_of(&self, q: Watched, t0: f64, t1: f64) -> impl Iterator<Item = &Extremum> + '_ {
        self.list
            .iter()
            .filter(move |e| e.quantity == q && e.t >= t0 && e.t <= t1)
    }

    /// The largest maximum (or smallest minimum) of `q` within `[t0, t1]`.
    pub fn extreme(&self, q: Watched, kind: ExtremumKind, t0: f64, t1: f64) -> Option<f64> {
        let values = self.of(q, kind, t0, t1).map(|e| e.value);
        match kind {
            ExtremumKind::Max => values.reduce(f64::max),
            ExtremumKind::Min => values.reduce(f64::min),
        }
    }

    /// The times of θ's cycle boundaries within `[t0, t1]`: its minima (`ExtremumKind::Min`)
    /// or maxima, those separated by a swing of [`PROMINENCE`] of the window's range.
    pub fn theta_cycles(&self, at: ExtremumKind, t0: f64, t1: f64) -> Vec<f64> {
        self.theta_turns(at, t0, t1).iter().map(|e| e.t).collect()
    }

    /// The extrema of θ behind [`Located::theta_cycles`] (its envelope, Fig. 2).
    pub fn theta_turns(&self, at: ExtremumKind, t0: f64, t1: f64) -> Vec<Extremum> {
        let in_window: Vec<&Extremum> = self
            .list
            .iter()
            .filter(|e| e.quantity == Watched::Theta && e.t >= t0 && e.t <= t1)
            .collect();
        let hi = in_window.iter().map(|e| e.value).fold(f64::MIN, f64::max);
        let lo = in_window.iter().map(|e| e.value).fold(f64::MAX, f64::min);
        let swing = PROMINENCE * (hi - lo);
        // Hysteresis: the candidate extreme of kind `at` is kept until θ has moved `swing`
        // away from it, then committed.
        let sign = if at == ExtremumKind::Min { 1.0 } else { -1.0 };
        let mut out = Vec::new();
        let mut candidate: Option<&Extremum> = None;
        // The farthest opposite turn since the last commit: a candidate the window ends on
        // counts if θ came to it from a swing away.
        let mut opposite = f64::MIN;
        for e in in_window {
            let v = sign * e.value;
            if e.kind == at {
                if candidate.is_none_or(|c| v < sign * c.value) {
                    candidate = Some(e);
                }
            } else if let Some(c) = candidate.filter(|c| v - sign * c.value > swing) {
                out.push(*c);
                candidate = None;
                opposite = v;
            } else {
                opposite = opposite.max(v);
            }
        }
        if let Some(c) = candidate.filter(|c| opposite - sign * c.value > swing) {
            out.push(*c);
        }
        out
    }

    /// The mean period of θ within `[t0, t1]`: between the first and the last cycle-bounding
    /// minimum, divided by the cycles between them; `None` with fewer than two.
    pub fn theta_period(&self, t0: f64, t1: f64) -> Option<f64> {
        let minima = self.theta_cycles(ExtremumKind::Min, t0, t1);
        let (first, last) = (minima.first()?, minima.last()?);
        (minima.len() >= 2).then(|| (last - first) / (minima.len() - 1) as f64)
    }

    /// For each cycle between consecutive `bounds`, the largest maximum of `q` in it.
    pub fn per_cycle_max(&self, q: Watched, bounds: &[f64]) -> Vec<Extremum> {
        bounds
            .windows(2)
            .filter_map(|w| {
                self.of(q, ExtremumKind::Max, w[0], w[1])
                    .max_by(|a, b| a.value.total_cmp(&b.value))
                    .copied()
            })
            .collect()
    }

    /// The table `extrema.csv` (or `.parquet`): one row per extremum, in time order, N as
    /// N/mg.
    pub fn table(&self) -> Table {
        let mut table = Table::new(EXTREMA_HEADER.split(','));
        table.rows = self
            .list
            .iter()
            .map(|e| {
                vec![
                    Cell::Float(e.t),
                    Cell::text(quantity_name(e.quantity)),
                    Cell::text(e.kind.name()),
                    Cell::Float(e.value),
                ]
            })
            .collect();
        table
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use equations::Mode;

    fn theta(t: f64, kind: ExtremumKind, value: f64) -> Extremum {
        Extremum {
            t,
            quantity: Watched::Theta,
            kind,
            value,
            theta: value,
            mode: Mode::Rolling,
            at_switch: false,
        }
    }

    #[test]
    fn ripples_do_not_make_cycles() {
        use ExtremumKind::{Max, Min};
        // Minima at 0, 1, 2 (θ = 0.1), maxima at 0.5, 1.5 (θ = 0.5); a ripple at 1.2/1.25.
        let list = [
            theta(0.0, Min, 0.1),
            theta(0.5, Max, 0.5),
            theta(1.0, Min, 0.1),
            theta(1.2, Max, 0.105),
            theta(1.25, Min, 0.104),
            theta(1.5, Max, 0.5),
            theta(2.0, Min, 0.1),
            theta(2.5, Max, 0.5),
        ];
        let located = Located::new(&list, 1.0);
        assert_eq!(located.theta_cycles(Min, 0.0, 3.0), vec![0.0, 1.0, 2.0]);
        assert_eq!(located.theta_period(0.0, 3.0), Some(1.0));
        // A window ending on a minimum keeps it: θ came down to it from a maximum.
        assert_eq!(located.theta_cycles(Min, 0.0, 2.2), vec![0.0, 1.0, 2.0]);
        assert_eq!(located.theta_cycles(Min, 0.9, 2.2), vec![1.0, 2.0]);
        // The maxima: the last one too, reached from a full swing.
        assert_eq!(located.theta_cycles(Max, 0.0, 3.0), vec![0.5, 1.5, 2.5]);
    }

    #[test]
    fn the_csv_lists_every_extremum_in_time_order_with_n_over_mg() {
        let mut n = theta(0.3, ExtremumKind::Max, 9.81);
        n.quantity = Watched::NormalForce;
        let located = Located::new(&[n, theta(0.1, ExtremumKind::Min, 0.2)], 4.905);
        assert_eq!(
            located.table().csv(),
            "t_s,quantity,kind,value\n0.1,theta_rad,min,0.2\n0.3,N_over_mg,max,2\n"
        );
    }
}
