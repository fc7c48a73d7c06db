//! The numbers of a solution's rows, stored column after column in one buffer, written row
//! by row as a run records them.
//!
//! Why columns: what readers take is a column or a block of them: a named column (a plot, a
//! check), the states as SciPy's `y` (shape `(states, rows)` in C order: exactly the columns
//! `1..=states` here), a NumPy array or a DataFrame column per name; all are slices of this
//! buffer, borrowed, never gathered. The one reader of whole rows, a CSV writer, reads a row
//! across the columns: a strided load per number, beside formatting it.
//!
//! Why one buffer written while the run records: a recording kept apart and copied into the
//! table at the end touches every number twice, and for a million samples the first touch
//! of fresh memory (the kernel's page faults) costs as much as the interpolation. The
//! recorder writes `t`, the state and the discrete values of each row straight into the
//! table, and the outputs are filled in at the end. The buffer grows as a vector does
//! (doubling, each column moved once per doubling), or is sized once when the number of rows
//! is known (given times), and is compacted when the run ends, so a finished table is one
//! array of `width × len` numbers.

/// A table of `f64`s stored column after column (see the module's documentation).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Trajectory {
    /// The number of rows.
    len: usize,
    /// The rows there is room for: column `k` is `values[k * capacity..][..len]`; equal to
    /// `len` once the table is finished.
    capacity: usize,
    /// The number of columns.
    width: usize,
    /// The columns, one after another.
    values: Vec<f64>,
}

impl Trajectory {
    /// An empty table of `width` columns, with room for `rows` rows.
    pub(crate) fn with_capacity(width: usize, rows: usize) -> Self {
        Trajectory {
            len: 0,
            capacity: rows,
            width,
            values: vec![0.0; width * rows],
        }
    }

    /// Appends a row whose first columns are `parts`, one after another (`t`, the state,
    /// ...); the columns after them stay zero until [`Trajectory::set`] writes them.
    pub(crate) fn push(&mut self, parts: &[&[f64]]) {
        if self.len == self.capacity {
            self.grow();
        }
        let (k, capacity) = (self.len, self.capacity);
        let mut column = 0;
        for part in parts {
            for &value in *part {
                self.values[column * capacity + k] = value;
                column += 1;
            }
        }
        debug_assert!(column <= self.width, "a row of {column} in {}", self.width);
        self.len += 1;
    }

    /// Twice the room (at least 64 rows), each column moved to its new place.
    fn grow(&mut self) {
        let capacity = (2 * self.capacity).max(64);
        let mut values = vec![0.0; self.width * capacity];
        for k in 0..self.width {
            values[k * capacity..][..self.len].copy_from_slice(self.column(k));
        }
        self.values = values;
        self.capacity = capacity;
    }

    /// Writes `values` into row `k` from column `first` on.
    pub(crate) fn set(&mut self, k: usize, first: usize, values: &[f64]) {
        assert!(k < self.len, "row {k} of {}", self.len);
        for (column, &value) in (first..).zip(values) {
            self.values[column * self.capacity + k] = value;
        }
    }

    /// The columns `first..first + count` of row `k` written into `into` (cleared first).
    pub(crate) fn read(&self, k: usize, first: usize, count: usize, into: &mut Vec<f64>) {
        assert!(k < self.len, "row {k} of {}", self.len);
        into.clear();
        into.extend((first..first + count).map(|column| self.values[column * self.capacity + k]));
    }

    /// The finished table: the columns moved together, the room left over given back.
    pub(crate) fn compacted(mut self) -> Self {
        if self.capacity != self.len {
            for k in 1..self.width {
                let from = k * self.capacity;
                self.values.copy_within(from..from + self.len, k * self.len);
            }
            self.values.truncate(self.width * self.len);
            self.values.shrink_to_fit();
            self.capacity = self.len;
        }
        self
    }

    /// The number of rows.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether there is no row.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The number of columns.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Column `k`, over all rows.
    ///
    /// # Panics
    /// If `k` is not below [`Trajectory::width`].
    pub fn column(&self, k: usize) -> &[f64] {
        assert!(k < self.width, "column {k} of {}", self.width);
        &self.values[k * self.capacity..][..self.len]
    }

    /// The columns `first..first + count`, one after another: a `(count, len)` array in C
    /// order (the states, columns `1..=states`, are SciPy's `y`).
    ///
    /// # Panics
    /// If the columns go past [`Trajectory::width`].
    pub fn columns(&self, first: usize, count: usize) -> &[f64] {
        assert!(
            first + count <= self.width,
            "columns {first}..{} of {}",
            first + count,
            self.width
        );
        debug_assert_eq!(self.capacity, self.len, "a finished table");
        &self.values[first * self.len..(first + count) * self.len]
    }

    /// Every column, one after another: a `(width, len)` array in C order.
    pub fn values(&self) -> &[f64] {
        self.columns(0, self.width)
    }

    /// The buffer of [`Trajectory::values`], given up (to be handed over whole).
    pub fn into_values(self) -> Vec<f64> {
        self.compacted().values
    }

    /// The number in row `k`, column `column`.
    pub fn get(&self, k: usize, column: usize) -> f64 {
        self.column(column)[k]
    }

    /// Row `k` written into `row` (cleared first): one buffer read from row to row.
    pub fn row_into(&self, k: usize, row: &mut Vec<f64>) {
        self.read(k, 0, self.width, row);
    }

    /// Row `k`, gathered from the columns.
    pub fn row(&self, k: usize) -> Vec<f64> {
        let mut row = Vec::with_capacity(self.width);
        self.row_into(k, &mut row);
        row
    }

    /// Every row in order, each gathered (for a reader of a few rows; a reader of many
    /// reuses one buffer with [`Trajectory::row_into`]).
    pub fn rows(&self) -> impl ExactSizeIterator<Item = Vec<f64>> + '_ {
        (0..self.len).map(|k| self.row(k))
    }

    /// The last row's first column (a recording's last time).
    pub(crate) fn last_first(&self) -> Option<f64> {
        self.len.checked_sub(1).map(|k| self.values[k])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rows of `width` numbers, each `1000 k + column`, pushed in two parts (the first
    /// `split` columns) and the rest set afterwards, as a recording and its outputs are.
    fn table(width: usize, rows: usize, room: usize, split: usize) -> Trajectory {
        let row = |k: usize| -> Vec<f64> { (0..width).map(|c| (1000 * k + c) as f64).collect() };
        let mut table = Trajectory::with_capacity(width, room);
        for k in 0..rows {
            let row = row(k);
            table.push(&[&row[..1], &row[1..split]]);
        }
        for k in 0..rows {
            table.set(k, split, &row(k)[split..]);
        }
        table
    }

    #[test]
    fn rows_pushed_are_rows_read_whatever_the_room() {
        for (rows, room) in [(0, 0), (1, 0), (5, 5), (63, 0), (64, 0), (65, 3), (1000, 7)] {
            let table = table(4, rows, room, 2);
            for finished in [table.clone(), table.compacted()] {
                assert_eq!(finished.len(), rows);
                for k in 0..rows {
                    let want: Vec<f64> = (0..4).map(|c| (1000 * k + c) as f64).collect();
                    assert_eq!(finished.row(k), want, "{rows} rows, room {room}");
                    for (c, &value) in want.iter().enumerate() {
                        assert_eq!(finished.column(c)[k], value);
                        assert_eq!(finished.get(k, c), value);
                    }
                }
                assert_eq!(
                    finished.last_first(),
                    rows.checked_sub(1).map(|k| 1000.0 * k as f64)
                );
            }
        }
    }

    #[test]
    fn a_finished_table_is_its_columns_one_after_another() {
        let table = table(3, 100, 1, 3).compacted();
        let columns: Vec<f64> = (0..3).flat_map(|c| table.column(c).to_vec()).collect();
        assert_eq!(table.values(), &columns[..]);
        assert_eq!(table.columns(1, 2), &columns[100..]);
        assert_eq!(table.clone().into_values(), columns);
        // Compacting twice, or a table sized exactly, changes nothing.
        assert_eq!(table.clone().compacted(), table);
        let exact = self::table(3, 100, 100, 3);
        assert_eq!(exact.compacted(), table);
    }
}
