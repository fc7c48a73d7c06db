//! Shards: a deterministic share of a sweep's points for one of n jobs.
//!
//! Point k belongs to shard `k mod n`: the shares differ by at most one point, and neighbours
//! along the last axis (often alike in cost) land in different shards. `--shard auto` reads
//! the share from the job engine: a Slurm job array (`SLURM_ARRAY_TASK_ID` counted from
//! `SLURM_ARRAY_TASK_MIN` in steps of `SLURM_ARRAY_TASK_STEP`, so that `--array=0-4:2` is
//! shards 0, 1, 2 of 3; `SLURM_ARRAY_TASK_COUNT`) or a Kubernetes Indexed Job
//! (`JOB_COMPLETION_INDEX`, with the count given as `--shard auto/N` since Kubernetes does not
//! export it).

use serde::{Deserialize, Serialize};

/// Shard `index` of `count` (counted from 0).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Shard {
    /// Which shard, 0-based.
    pub index: usize,
    /// How many shards.
    pub count: usize,
}

/// Why a `--shard` value cannot be used.
#[derive(Debug, PartialEq, thiserror::Error)]
#[error("--shard `{spec}`: {problem}")]
pub struct ShardError {
    /// The value as given.
    pub spec: String,
    /// What is wrong (naming the environment variable when it is one).
    pub problem: String,
}

impl Shard {
    /// Parses `i/n`, `auto` or `auto/n`; `env` looks up environment variables.
    pub fn parse(spec: &str, env: impl Fn(&str) -> Option<String>) -> Result<Shard, ShardError> {
        let bad = |problem: String| ShardError {
            spec: spec.to_string(),
            problem,
        };
        let number = |what: &str, text: &str| {
            text.trim()
                .parse::<usize>()
                .map_err(|_| bad(format!("{what} must be a whole number ≥ 0, got `{text}`")))
        };
        let (first, count) = match spec.split_once('/') {
            Some((i, n)) => (i.trim(), Some(number("the shard count", n)?)),
            None => (spec.trim(), None),
        };
        let shard = if first == "auto" {
            if let Some(id) = env("SLURM_ARRAY_TASK_ID") {
                let id = number("SLURM_ARRAY_TASK_ID", &id)?;
                let min = env("SLURM_ARRAY_TASK_MIN")
                    .map(|m| number("SLURM_ARRAY_TASK_MIN", &m))
                    .transpose()?
                    .unwrap_or(0);
                let count = match (count, env("SLURM_ARRAY_TASK_COUNT")) {
                    (Some(n), _) => n,
                    (None, Some(n)) => number("SLURM_ARRAY_TASK_COUNT", &n)?,
                    (None, None) => {
                        return Err(bad(
                            "SLURM_ARRAY_TASK_COUNT is not set: give the count as `auto/N`".into(),
                        ))
                    }
                };
                let step = env("SLURM_ARRAY_TASK_STEP")
                    .map(|s| number("SLURM_ARRAY_TASK_STEP", &s))
                    .transpose()?
                    .unwrap_or(1)
                    .max(1);
                let offset = id.checked_sub(min).ok_or_else(|| {
                    bad(format!(
                        "SLURM_ARRAY_TASK_ID = {id} is below SLURM_ARRAY_TASK_MIN = {min}"
                    ))
                })?;
                if offset % step != 0 {
                    return Err(bad(format!(
                        "SLURM_ARRAY_TASK_ID = {id} is not SLURM_ARRAY_TASK_MIN = {min} plus a multiple of SLURM_ARRAY_TASK_STEP = {step}: an array given as a list needs `--shard i/n`"
                    )));
                }
                Shard {
                    index: offset / step,
                    count,
                }
            } else if let Some(id) = env("JOB_COMPLETION_INDEX") {
                let index = number("JOB_COMPLETION_INDEX", &id)?;
                let count = count.ok_or_else(|| {
                    bad("JOB_COMPLETION_INDEX is set but the count is not: use `auto/N` with N the Job's completions".into())
                })?;
                Shard { index, count }
            } else {
                return Err(bad(
                    "neither SLURM_ARRAY_TASK_ID nor JOB_COMPLETION_INDEX is set".into(),
                ));
            }
        } else {
            let count = count.ok_or_else(|| bad("expected `i/n`, `auto` or `auto/n`".into()))?;
            Shard {
                index: number("the shard index", first)?,
                count,
            }
        };
        if shard.count == 0 || shard.index >= shard.count {
            return Err(bad(format!(
                "shard {} of {} does not exist (shards are numbered 0 to n-1, n ≥ 1)",
                shard.index, shard.count
            )));
        }
        Ok(shard)
    }

    /// Whether point `point` is in this shard.
    pub fn contains(self, point: usize) -> bool {
        point % self.count == self.index
    }

    /// Whether `point` is run under `shard` (every point when there is none).
    pub fn selects(shard: Option<Shard>, point: usize) -> bool {
        shard.is_none_or(|s| s.contains(point))
    }

    /// The folder a shard writes into, under the sweep's `--out`.
    pub fn folder(self) -> String {
        format!("shard-{}-of-{}", self.index, self.count)
    }

    /// `i/n`, or `whole sweep`.
    pub fn label(shard: Option<Shard>) -> String {
        shard.map_or("the whole sweep".to_string(), |s| {
            format!("{}/{}", s.index, s.count)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn env<'a>(vars: &'a [(&'a str, &'a str)]) -> impl Fn(&str) -> Option<String> + 'a {
        move |k| {
            vars.iter()
                .find(|(n, _)| *n == k)
                .map(|(_, v)| v.to_string())
        }
    }

    #[test]
    fn explicit_and_engine_shards() {
        assert_eq!(
            Shard::parse("2/5", env(&[])),
            Ok(Shard { index: 2, count: 5 })
        );
        let slurm = [
            ("SLURM_ARRAY_TASK_ID", "4"),
            ("SLURM_ARRAY_TASK_MIN", "1"),
            ("SLURM_ARRAY_TASK_COUNT", "4"),
        ];
        assert_eq!(
            Shard::parse("auto", env(&slurm)),
            Ok(Shard { index: 3, count: 4 })
        );
        // `--array=0-4:2`: tasks 0, 2, 4 are shards 0, 1, 2 of 3.
        for (id, index) in [("0", 0), ("2", 1), ("4", 2)] {
            let stepped = [
                ("SLURM_ARRAY_TASK_ID", id),
                ("SLURM_ARRAY_TASK_MIN", "0"),
                ("SLURM_ARRAY_TASK_MAX", "4"),
                ("SLURM_ARRAY_TASK_STEP", "2"),
                ("SLURM_ARRAY_TASK_COUNT", "3"),
            ];
            assert_eq!(
                Shard::parse("auto", env(&stepped)),
                Ok(Shard { index, count: 3 })
            );
        }
        let k8s = [("JOB_COMPLETION_INDEX", "0")];
        assert_eq!(
            Shard::parse("auto/3", env(&k8s)),
            Ok(Shard { index: 0, count: 3 })
        );
        assert!(Shard::parse("auto", env(&k8s))
            .unwrap_err()
            .problem
            .contains("auto/N"));
    }

    #[test]
    fn bad_shards_say_why() {
        for (spec, vars, word) in [
            ("3/3", &[][..], "does not exist"),
            ("1/0", &[], "does not exist"),
            ("x/2", &[], "`x`"),
            ("2", &[], "expected"),
            ("auto", &[], "neither"),
            (
                "auto",
                &[("SLURM_ARRAY_TASK_ID", "a")][..],
                "SLURM_ARRAY_TASK_ID",
            ),
            (
                "auto",
                &[
                    ("SLURM_ARRAY_TASK_ID", "3"),
                    ("SLURM_ARRAY_TASK_STEP", "2"),
                    ("SLURM_ARRAY_TASK_COUNT", "3"),
                ][..],
                "SLURM_ARRAY_TASK_STEP",
            ),
        ] {
            let e = Shard::parse(spec, env(vars)).unwrap_err();
            assert!(e.to_string().contains(word), "{spec}: {e}");
        }
    }

    #[test]
    fn shards_partition_the_points() {
        let n = 4;
        for point in 0..50 {
            let owners = (0..n)
                .filter(|&i| Shard { index: i, count: n }.contains(point))
                .count();
            assert_eq!(owners, 1);
        }
    }
}
