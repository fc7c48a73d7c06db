//! Parquet output and the scene's fine-sampling windows, read back with the Rust Parquet
//! reader: the same run written as CSV and as Parquet holds the same columns, names and
//! values to the bit, typed; a window adds exactly its grid's samples to the trajectory file
//! and changes nothing else.

use std::fs;
use std::path::Path;
use std::sync::atomic::AtomicBool;

use arrow_schema::DataType;
use eulerdisk::{load_scene, split_fields, Cell, Override, Scene};
use eulerdisk_parquet::read_table as read_parquet;
use parquet::arrow::arrow_reader::ParquetRecordBatchReaderBuilder;

use super::quiet_run::{run_quietly, Quiet};

/// `tangent-toy-pruned` for `t_end` seconds at `rate`, with `extra` overrides; the command
/// line's Parquet writer installed, as the command line installs it.
fn scene(t_end: f64, rate: f64, extra: &[Override]) -> (Scene, Vec<Override>) {
    eulerdisk_parquet::install();
    let mut overrides = vec![
        Override::new("run", "t_end", t_end),
        Override::new("run", "sample_rate", rate),
    ];
    overrides.extend_from_slice(extra);
    (
        load_scene("tangent-toy-pruned", &overrides).unwrap(),
        overrides,
    )
}

/// `output.windows` as an override.
fn windows(text: &str) -> Override {
    let table: toml::Table = toml::from_str(&format!("w = {text}")).unwrap();
    Override::at("output.windows", table["w"].clone()).unwrap()
}

/// A CSV file's cells, each field read back as the Parquet writer types it.
fn csv_cells(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let text = fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header = split_fields(lines.next().unwrap());
    (header, lines.map(split_fields).collect())
}

/// Whether a Parquet cell holds what a CSV field says (numbers to the bit).
fn same(cell: &Cell, field: &str) -> bool {
    match cell {
        Cell::Null => field.is_empty(),
        Cell::Float(v) => field
            .parse::<f64>()
            .is_ok_and(|f| f.to_bits() == v.to_bits()),
        Cell::Int(i) => field.parse::<i64>() == Ok(*i),
        Cell::Bool(b) => field.parse::<bool>() == Ok(*b),
        Cell::Text(s) => s == field,
    }
}

fn run(scene: &Scene, overrides: &[Override]) -> (tempfile::TempDir, eulerdisk::RunReport) {
    let how = Quiet {
        trajectory: true,
        ..Quiet::default()
    };
    run_quietly(scene, overrides, how, &AtomicBool::new(false))
}

#[test]
fn parquet_tables_hold_the_csv_values_typed() {
    let (csv_scene, csv_sets) = scene(2.0, 1000.0, &[]);
    let format = Override::parse("output.format=parquet").unwrap();
    let (pq_scene, pq_sets) = scene(2.0, 1000.0, &[format]);
    let (csv_dir, csv_report) = run(&csv_scene, &csv_sets);
    let (pq_dir, pq_report) = run(&pq_scene, &pq_sets);
    assert_eq!(
        csv_report.summary.transitions,
        pq_report.summary.transitions
    );
    for stem in ["trajectory", "events", "extrema"] {
        let pq_path = pq_dir.path().join(format!("{stem}.parquet"));
        assert!(
            !pq_dir.path().join(format!("{stem}.csv")).exists(),
            "{stem}"
        );
        let (header, rows) = csv_cells(&csv_dir.path().join(format!("{stem}.csv")));
        let table = read_parquet(&pq_path).unwrap();
        assert_eq!(table.header, header, "{stem}");
        assert_eq!(table.rows.len(), rows.len(), "{stem}");
        assert!(rows.len() > 1, "{stem}");
        for (r, (cells, fields)) in table.rows.iter().zip(&rows).enumerate() {
            for (c, (cell, field)) in cells.iter().zip(fields).enumerate() {
                assert!(
                    same(cell, field),
                    "{stem} row {r} `{}`: {cell:?} against {field:?}",
                    header[c]
                );
            }
        }
    }
    // The types, as another reader sees them: numbers Float64, words Utf8.
    let file = fs::File::open(pq_dir.path().join("trajectory.parquet")).unwrap();
    let reader = ParquetRecordBatchReaderBuilder::try_new(file).unwrap();
    let schema = reader.schema().clone();
    assert_eq!(schema.field(0).name(), "t_s");
    assert_eq!(schema.field(0).data_type(), &DataType::Float64);
    assert_eq!(schema.field(1).name(), "mode");
    assert_eq!(schema.field(1).data_type(), &DataType::Utf8);
    assert!(schema.fields()[2..]
        .iter()
        .all(|f| f.data_type() == &DataType::Float64));
    let events = read_parquet(&pq_dir.path().join("events.parquet")).unwrap();
    let last = events.rows.last().unwrap();
    assert_eq!(
        (&last[2], &last[4]),
        (&Cell::text("stop"), &Cell::Null),
        "{last:?}"
    );
    // A rerun as CSV into the Parquet folder leaves no Parquet table of the earlier run.
    let opts = eulerdisk::RunOptions {
        out_dir: pq_dir.path().to_path_buf(),
        progress: eulerdisk::ProgressStyle::Quiet,
        backend: eulerdisk::Backend::Generated,
        engine: eulerdisk::DEFAULT_ENGINE,
        figures: false,
        trajectory: true,
        provenance: eulerdisk::Provenance::new(&csv_scene, "tangent-toy-pruned", &csv_sets),
    };
    eulerdisk::run_scene(&csv_scene, &opts, &AtomicBool::new(false)).unwrap();
    assert!(!pq_dir.path().join("trajectory.parquet").exists());
    assert!(pq_dir.path().join("trajectory.csv").is_file());
}

#[test]
fn a_window_adds_its_grid_to_the_trajectory_and_changes_nothing_else() {
    let (plain, plain_sets) = scene(2.0, 100.0, &[]);
    let window = windows("[{ from = 1.0, to = 1.01, sample_rate = 20000 }]");
    let (fine, fine_sets) = scene(2.0, 100.0, &[window]);
    let (plain_dir, plain_report) = run(&plain, &plain_sets);
    let (fine_dir, fine_report) = run(&fine, &fine_sets);
    let times = |dir: &Path| -> Vec<f64> {
        let (_, rows) = csv_cells(&dir.join("trajectory.csv"));
        rows.iter().map(|r| r[0].parse().unwrap()).collect()
    };
    let (coarse, refined) = (times(plain_dir.path()), times(fine_dir.path()));
    assert_eq!(coarse.len(), 201);
    // 201 window samples at 20 kHz, two of which (1.0 and 1.01) are on the 100 Hz grid.
    assert_eq!(refined.len(), 201 + 199, "{}", refined.len());
    assert!(refined.windows(2).all(|w| w[0] < w[1]), "in time order");
    let inside: Vec<f64> = refined
        .iter()
        .copied()
        .filter(|t| (1.0..=1.01).contains(t))
        .collect();
    assert_eq!(inside.len(), 201);
    assert!(inside
        .windows(2)
        .all(|w| ((w[1] - w[0]) - 5e-5).abs() < 1e-12));
    let outside: Vec<f64> = refined
        .iter()
        .copied()
        .filter(|t| !(1.0..=1.01).contains(t))
        .collect();
    let coarse_outside: Vec<f64> = coarse
        .iter()
        .copied()
        .filter(|t| !(1.0..=1.01).contains(t))
        .collect();
    assert_eq!(outside, coarse_outside);
    // The samples both files share are the same; the analysis sees the same grid.
    let (_, plain_rows) = csv_cells(&plain_dir.path().join("trajectory.csv"));
    let (_, fine_rows) = csv_cells(&fine_dir.path().join("trajectory.csv"));
    for row in &plain_rows {
        assert!(fine_rows.contains(row), "{row:?}");
    }
    let (a, b) = (&plain_report.summary, &fine_report.summary);
    assert_eq!(a.transitions, b.transitions);
    assert_eq!(
        plain_report.data.samples.len(),
        fine_report.data.samples.len()
    );
    assert_eq!(
        fs::read(plain_dir.path().join("events.csv")).unwrap(),
        fs::read(fine_dir.path().join("events.csv")).unwrap()
    );
}

#[test]
fn bad_windows_are_named_by_key_all_at_once() {
    let cases = [
        (
            "[{ from = 1.0, to = 3.0, sample_rate = 150 }]",
            vec!["output.windows[0].to", "output.windows[0].sample_rate"],
        ),
        (
            "[{ from = 0.5, to = 0.6, sample_rate = 200 }, { from = 0.7, to = 0.6, sample_rate = -1 }]",
            vec!["output.windows[1].to", "output.windows[1].sample_rate"],
        ),
        ("[{ from = 0.5, to = 0.6, rate = 200 }]", vec!["output.windows[0]"]),
        (
            "[{ from = 0.0, to = 2.0, sample_rate = 1e9 }]",
            vec!["output.windows"],
        ),
    ];
    for (text, keys) in cases {
        let overrides = [
            Override::new("run", "t_end", 2.0),
            Override::new("run", "sample_rate", 100.0),
            windows(text),
        ];
        let err = load_scene("tangent-toy-pruned", &overrides).unwrap_err();
        let said = err.to_string();
        for key in &keys {
            assert!(said.contains(key), "{text}: {said}");
        }
        if keys.len() > 1 {
            assert_eq!(err.keys().len(), keys.len(), "{text}: {said}");
        }
    }
}
