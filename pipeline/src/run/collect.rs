//! Keeps what a run streams, sorted by the [`SamplePlan`]: the trajectory's grid (also
//! written to the trajectory file as it arrives, when a file is given), and the finely
//! sampled first and last second for the figures.

use super::plan::{SamplePlan, Window};
use super::trajectory::TrajectoryFile;
use crate::output::atomic::WriteError;
use crate::record::RunData;
use equations::record::Sample;
use equations::{Mode, TransitionRecord};

/// Collects a run's stream.
#[derive(Debug)]
pub struct Collector {
    plan: SamplePlan,
    data: RunData,
    latest: Option<Sample>,
    file: Option<TrajectoryFile>,
}

impl Collector {
    /// An empty collector that keeps the samples of `plan`.
    pub fn new(plan: SamplePlan) -> Collector {
        Collector {
            plan,
            data: RunData::default(),
            latest: None,
            file: None,
        }
    }

    /// Also writes every trajectory sample into `file` as it arrives.
    pub fn writing(mut self, file: TrajectoryFile) -> Collector {
        self.file = Some(file);
        self
    }

    /// Takes one sample of the plan.
    pub fn sample(&mut self, s: Sample) -> Result<(), WriteError> {
        if self.plan.is_written(s.t) {
            if let Some(file) = &mut self.file {
                file.row(&s)?;
            }
            // The scene's windows go to the file only: the analysis sees the one grid.
            if self.plan.is_coarse(s.t) {
                self.data.samples.push(s);
            }
        }
        match self.plan.window(s.t) {
            Some(Window::First) => self.data.first_second.push(s),
            Some(Window::Last) => self.data.last_second.push(s),
            None => {}
        }
        self.latest = Some(s);
        Ok(())
    }

    /// Takes one mode decision.
    pub fn event(&mut self, e: TransitionRecord) {
        self.data.events.push(e);
    }

    /// Takes located extrema.
    pub fn extrema(&mut self, batch: Vec<equations::Extremum>) {
        self.data.extrema.extend(batch);
    }

    /// Takes the last second of a run that ended before the plan's last window.
    pub fn last_second(&mut self, samples: Vec<Sample>) {
        self.data.last_second = samples;
    }

    /// Whether it writes the trajectory file as the samples arrive.
    pub fn writes_file(&self) -> bool {
        self.file.is_some()
    }

    /// The time of the latest sample or event: where a run that failed was last heard of
    /// (its events may have gone on past its last sample).
    pub fn latest_t(&self) -> Option<f64> {
        let sample = self.latest.map(|s| s.t);
        let event = self.data.events.last().map(|e| e.t);
        match (sample, event) {
            (Some(s), Some(e)) => Some(s.max(e)),
            (s, e) => s.or(e),
        }
    }

    /// The mode of the latest sample or event.
    pub fn latest_mode(&self) -> Option<Mode> {
        let sample = self.latest.map(|s| (s.t, s.mode));
        let event = self.data.events.last().map(|e| (e.t, e.to));
        match (sample, event) {
            (Some(s), Some(e)) => Some(if e.0 >= s.0 { e.1 } else { s.1 }),
            (s, e) => s.or(e).map(|x| x.1),
        }
    }

    /// Everything collected, with `last` (the exact final state, if known) ending the
    /// trajectory when it lies beyond its last row; the file, if any, is handed back complete
    /// but not yet committed.
    pub fn finish(
        mut self,
        last: Option<Sample>,
    ) -> Result<(RunData, Option<TrajectoryFile>), WriteError> {
        let end = last.or(self.latest);
        if let Some(end) = end {
            if self.data.samples.last().is_none_or(|s| s.t < end.t) {
                if let Some(file) = &mut self.file {
                    file.row(&end)?;
                }
                self.data.samples.push(end);
            }
        }
        Ok((self.data, self.file))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::synthetic::SyntheticRun;
    use crate::output::format::TableFormat;
    use equations::record::Quantity;

    #[test]
    fn keeps_the_trajectory_grid_and_both_windows() {
        let p = equations::DiskParams::paper();
        let fine = SyntheticRun {
            period: 0.1,
            t_end: 3.0,
            rate: 2000.0,
        }
        .data(&p)
        .samples;
        let plan = SamplePlan {
            every: 20,
            ..SamplePlan::new(0.0, 3.0, 100.0)
        };
        let mut c = Collector::new(plan.clone());
        for s in fine.iter().filter(|s| plan.wants(s.t)) {
            c.sample(*s).unwrap();
        }
        let (d, file) = c.finish(None).unwrap();
        assert!(file.is_none());
        assert_eq!(d.samples.len(), 301);
        assert_eq!(d.samples[1].t, fine[20].t);
        assert_eq!(d.first_second.len(), 2001);
        assert_eq!(d.last_second.first().unwrap().t, 2.0);
        assert_eq!(d.last_second.last().unwrap().t, 3.0);
    }

    #[test]
    fn the_final_state_ends_the_trajectory_and_the_file() {
        let p = equations::DiskParams::paper();
        let run = SyntheticRun {
            period: 0.1,
            t_end: 2.0,
            rate: 100.0,
        }
        .data(&p)
        .samples;
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("trajectory.csv");
        let file =
            TrajectoryFile::create(dir.path(), TableFormat::Csv, &[Quantity::Theta], p).unwrap();
        let mut c = Collector::new(SamplePlan::new(0.0, 2.0, 100.0)).writing(file);
        for s in &run[..150] {
            c.sample(*s).unwrap();
        }
        let mut last = run[150];
        last.t = 1.4973;
        let (d, file) = c.finish(Some(last)).unwrap();
        assert_eq!(d.samples.last().unwrap().t, 1.4973);
        assert!(!path.exists(), "not committed yet");
        file.unwrap().commit().unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        assert_eq!(text.lines().count(), 1 + 151);
        assert!(text.lines().last().unwrap().starts_with("1.4973,"));
    }
}
