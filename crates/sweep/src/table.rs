//! The per-cell table: the [`CellRecord`]s of a sweep as the rows of a CSV file ([`csv()`]) or a
//! Parquet file ([`parquet()`]).
//!
//! The columns are the record's fields, in their order and under their names; the record's docs say
//! what each one means. One list in this module defines every column once — its name, its Parquet
//! type, whether it may be empty and how to read it from a record — and both writers follow it.
//! Each field's type gives its column's form:
//!
//! | field | CSV | Parquet |
//! |---|---|---|
//! | `String` | the text, quoted (RFC 4180, quotes doubled) when it holds a comma, quote, CR or LF | `BYTE_ARRAY` annotated `STRING` (UTF-8) |
//! | `u64` | decimal | `INT64`; a value above `i64::MAX` is an error ([`TableError::OutOfRange`]) |
//! | `u32` | decimal | `INT64` too: every `u32` fits, and the table keeps one integer type |
//! | `f64` | shortest round-trip form (`{:?}`: `0.25`, `1e-7`, `-0.0`, `inf`, `NaN`), read back bit for bit | `DOUBLE` |
//! | `bool` | `true` / `false` | `BOOLEAN` |
//! | `Option<_>` | an empty field for `None` | as the inner type, `OPTIONAL`, null for `None` |
//!
//! Every other column is `REQUIRED`. Only an empty `undefined_reason` reads the same as a missing
//! one in CSV; Parquet tells them apart.
//!
//! Both writers are deterministic: the same records give the same bytes. The CSV has a header line
//! and one line per record, each ended by LF. The Parquet file is uncompressed, holds every record
//! in one row group and is written with the parquet crate's default (Parquet 1.0) writer
//! properties; its `created_by` names that crate's version, which `Cargo.lock` pins. pandas
//! (pyarrow) and polars read it.

use std::fmt::{self, Write as _};
use std::sync::Arc;

use parquet::basic::{Compression, LogicalType, Repetition, Type as PhysicalType};
use parquet::data_type::{BoolType, ByteArray, ByteArrayType, DataType, DoubleType, Int64Type};
use parquet::errors::ParquetError;
use parquet::file::properties::{WriterProperties, WriterVersion};
use parquet::file::writer::{SerializedColumnWriter, SerializedFileWriter};
use parquet::schema::types::Type;

use shadowlab_analysis::report::csv_field;

use crate::record::CellRecord;

/// Why the Parquet table could not be written.
#[derive(Debug)]
pub enum TableError {
    /// The parquet crate refused the schema or a write.
    Parquet(ParquetError),
    /// A `u64` field holds a value that Parquet's signed `INT64` cannot.
    OutOfRange {
        /// The column's name.
        column: &'static str,
        /// The record's index in the slice written.
        row: usize,
        /// The value.
        value: u64,
    },
}

impl fmt::Display for TableError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Parquet(error) => write!(f, "cannot write the Parquet table: {error}"),
            Self::OutOfRange { column, row, value } => write!(
                f,
                "cannot write the Parquet table: `{column}` of row {row} is {value}, above the \
                 largest INT64 ({})",
                i64::MAX
            ),
        }
    }
}

impl std::error::Error for TableError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Parquet(error) => Some(error),
            Self::OutOfRange { .. } => None,
        }
    }
}

impl From<ParquetError> for TableError {
    fn from(error: ParquetError) -> Self {
        Self::Parquet(error)
    }
}

/// How a column reads its value from a record; the variant is the field's type, and gives the
/// column's Parquet type and repetition.
#[derive(Clone, Copy)]
enum Value {
    /// A `String` field.
    Str(fn(&CellRecord) -> &str),
    /// An `Option<String>` field.
    OptStr(fn(&CellRecord) -> Option<&str>),
    /// A `u64` field.
    U64(fn(&CellRecord) -> u64),
    /// An `Option<u64>` field.
    OptU64(fn(&CellRecord) -> Option<u64>),
    /// A `u32` field.
    U32(fn(&CellRecord) -> u32),
    /// An `f64` field.
    F64(fn(&CellRecord) -> f64),
    /// An `Option<f64>` field.
    OptF64(fn(&CellRecord) -> Option<f64>),
    /// A `bool` field.
    Bool(fn(&CellRecord) -> bool),
}

/// One column of the table.
#[derive(Clone, Copy)]
struct Column {
    /// The column's name: the field's.
    name: &'static str,
    /// The field's type and how to read it.
    value: Value,
}

/// The column named `name`, read by `value`.
const fn column(name: &'static str, value: Value) -> Column {
    Column { name, value }
}

/// The table's columns: `CellRecord`'s fields, in its order.
const COLUMNS: [Column; 26] = [
    column("cell", Value::U64(|r| r.cell)),
    column("scene", Value::Str(|r| &r.scene)),
    column("camera", Value::U32(|r| r.camera)),
    column("light", Value::U32(|r| r.light)),
    column("light_x", Value::F64(|r| r.light_x)),
    column("light_y", Value::F64(|r| r.light_y)),
    column("light_z", Value::F64(|r| r.light_z)),
    column("gamma_deg", Value::F64(|r| r.gamma_deg)),
    column("technique", Value::Str(|r| &r.technique)),
    column("resolution", Value::U32(|r| r.resolution)),
    column("partitions", Value::U32(|r| r.partitions)),
    column("filter", Value::Str(|r| &r.filter)),
    column("defined", Value::Bool(|r| r.defined)),
    column(
        "undefined_reason",
        Value::OptStr(|r| r.undefined_reason.as_deref()),
    ),
    column("visible", Value::U64(|r| r.visible)),
    column("misclassified", Value::OptU64(|r| r.misclassified)),
    column("falsely_lit", Value::OptU64(|r| r.falsely_lit)),
    column("falsely_shadowed", Value::OptU64(|r| r.falsely_shadowed)),
    column("texels", Value::OptU64(|r| r.texels)),
    column("footprint_max", Value::OptF64(|r| r.footprint_max)),
    column("footprint_p99", Value::OptF64(|r| r.footprint_p99)),
    column("footprint_mean", Value::OptF64(|r| r.footprint_mean)),
    column("planning_ms", Value::OptF64(|r| r.planning_ms)),
    column("shadow_pass_ms", Value::OptF64(|r| r.shadow_pass_ms)),
    column("lookup_ms", Value::OptF64(|r| r.lookup_ms)),
    column("cell_ms", Value::F64(|r| r.cell_ms)),
];

impl Column {
    /// The column's field of `record` as CSV: empty for `None`.
    fn csv_field(&self, record: &CellRecord, out: &mut String) {
        // Writing to a `String` cannot fail.
        let _ = match self.value {
            Value::Str(get) => write_text(get(record), out),
            Value::OptStr(get) => get(record).map_or(Ok(()), |text| write_text(text, out)),
            Value::U64(get) => write!(out, "{}", get(record)),
            Value::OptU64(get) => get(record).map_or(Ok(()), |v| write!(out, "{v}")),
            Value::U32(get) => write!(out, "{}", get(record)),
            Value::F64(get) => write!(out, "{:?}", get(record)),
            Value::OptF64(get) => get(record).map_or(Ok(()), |v| write!(out, "{v:?}")),
            Value::Bool(get) => write!(out, "{}", get(record)),
        };
    }

    /// The column's Parquet schema node.
    fn parquet_type(&self) -> Result<Type, ParquetError> {
        let (physical, logical, optional) = match self.value {
            Value::Str(_) => (PhysicalType::BYTE_ARRAY, Some(LogicalType::String), false),
            Value::OptStr(_) => (PhysicalType::BYTE_ARRAY, Some(LogicalType::String), true),
            Value::U64(_) | Value::U32(_) => (PhysicalType::INT64, None, false),
            Value::OptU64(_) => (PhysicalType::INT64, None, true),
            Value::F64(_) => (PhysicalType::DOUBLE, None, false),
            Value::OptF64(_) => (PhysicalType::DOUBLE, None, true),
            Value::Bool(_) => (PhysicalType::BOOLEAN, None, false),
        };
        let repetition = if optional {
            Repetition::OPTIONAL
        } else {
            Repetition::REQUIRED
        };
        Type::primitive_type_builder(self.name, physical)
            .with_repetition(repetition)
            .with_logical_type(logical)
            .build()
    }

    /// Writes the column's field of every record into `chunk`, the column's chunk of the row group.
    fn write_parquet(
        &self,
        records: &[CellRecord],
        chunk: &mut SerializedColumnWriter<'_>,
    ) -> Result<(), TableError> {
        match self.value {
            Value::Str(get) => {
                let values: Vec<ByteArray> = records.iter().map(|r| get(r).into()).collect();
                write_required::<ByteArrayType>(chunk, &values)?;
            }
            Value::OptStr(get) => {
                write_optional::<ByteArrayType>(
                    chunk,
                    records.iter().map(|r| get(r).map(Into::into)),
                )?;
            }
            Value::U64(get) => {
                let values = records
                    .iter()
                    .enumerate()
                    .map(|(row, r)| self.int64(row, get(r)))
                    .collect::<Result<Vec<i64>, TableError>>()?;
                write_required::<Int64Type>(chunk, &values)?;
            }
            Value::OptU64(get) => {
                let cells = records
                    .iter()
                    .enumerate()
                    .map(|(row, r)| get(r).map(|v| self.int64(row, v)).transpose())
                    .collect::<Result<Vec<Option<i64>>, TableError>>()?;
                write_optional::<Int64Type>(chunk, cells)?;
            }
            Value::U32(get) => {
                let values: Vec<i64> = records.iter().map(|r| i64::from(get(r))).collect();
                write_required::<Int64Type>(chunk, &values)?;
            }
            Value::F64(get) => {
                let values: Vec<f64> = records.iter().map(get).collect();
                write_required::<DoubleType>(chunk, &values)?;
            }
            Value::OptF64(get) => write_optional::<DoubleType>(chunk, records.iter().map(get))?,
            Value::Bool(get) => {
                let values: Vec<bool> = records.iter().map(get).collect();
                write_required::<BoolType>(chunk, &values)?;
            }
        }
        Ok(())
    }

    /// `value`, of this column in row `row`, as Parquet's `INT64`.
    fn int64(&self, row: usize, value: u64) -> Result<i64, TableError> {
        i64::try_from(value).map_err(|_| TableError::OutOfRange {
            column: self.name,
            row,
            value,
        })
    }
}

/// Appends `text` as one CSV field, quoted as the study's tables quote it
/// (`shadowlab_analysis::report::csv_field`, RFC 4180).
fn write_text(text: &str, out: &mut String) -> fmt::Result {
    out.write_str(&csv_field(text))
}

/// Writes a `REQUIRED` column's values.
fn write_required<T: DataType>(
    chunk: &mut SerializedColumnWriter<'_>,
    values: &[T::T],
) -> Result<(), ParquetError> {
    chunk.typed::<T>().write_batch(values, None, None)?;
    Ok(())
}

/// Writes an `OPTIONAL` column's cells: a definition level per row (1 for a value, 0 for null) and
/// the values that are there.
fn write_optional<T: DataType>(
    chunk: &mut SerializedColumnWriter<'_>,
    cells: impl IntoIterator<Item = Option<T::T>>,
) -> Result<(), ParquetError> {
    let mut levels = Vec::new();
    let mut values = Vec::new();
    for cell in cells {
        levels.push(i16::from(cell.is_some()));
        values.extend(cell);
    }
    chunk
        .typed::<T>()
        .write_batch(&values, Some(&levels), None)?;
    Ok(())
}

/// The table as CSV: a header line with the column names, then one line per record in the order
/// given.
#[must_use]
pub fn csv(records: &[CellRecord]) -> String {
    let mut out = String::new();
    for (i, column) in COLUMNS.iter().enumerate() {
        if i > 0 {
            out.push(',');
        }
        out.push_str(column.name);
    }
    out.push('\n');
    for record in records {
        for (i, column) in COLUMNS.iter().enumerate() {
            if i > 0 {
                out.push(',');
            }
            column.csv_field(record, &mut out);
        }
        out.push('\n');
    }
    out
}

/// The table as a Parquet file, in memory: one uncompressed row group holding every record, in the
/// order given.
///
/// # Errors
///
/// [`TableError::OutOfRange`] if a `u64` field is above `i64::MAX`; [`TableError::Parquet`] if the
/// parquet crate fails.
pub fn parquet(records: &[CellRecord]) -> Result<Vec<u8>, TableError> {
    let fields = COLUMNS
        .iter()
        .map(|column| column.parquet_type().map(Arc::new))
        .collect::<Result<Vec<_>, ParquetError>>()?;
    let schema = Type::group_type_builder("cell_record")
        .with_fields(fields)
        .build()?;
    let properties = WriterProperties::builder()
        .set_writer_version(WriterVersion::PARQUET_1_0)
        .set_compression(Compression::UNCOMPRESSED)
        .build();
    let mut writer = SerializedFileWriter::new(Vec::new(), Arc::new(schema), Arc::new(properties))?;
    let mut row_group = writer.next_row_group()?;
    for column in &COLUMNS {
        let Some(mut chunk) = row_group.next_column()? else {
            return Err(ParquetError::General(format!(
                "the schema has no column `{}`",
                column.name
            ))
            .into());
        };
        column.write_parquet(records, &mut chunk)?;
        chunk.close()?;
    }
    row_group.close()?;
    Ok(writer.into_inner()?)
}

#[cfg(test)]
mod tests {
    use std::io::Write as _;

    use parquet::file::reader::{FileReader, SerializedFileReader};
    use parquet::record::{Field, Row};

    use super::{COLUMNS, TableError, csv, parquet};

    use crate::record::CellRecord;

    /// A defined cell with every field set.
    fn defined(cell: u64) -> CellRecord {
        CellRecord {
            cell,
            scene: "outdoor".to_owned(),
            camera: 2,
            light: 7,
            light_x: 0.1 + 0.2,
            light_y: -0.0,
            light_z: 1e-300,
            gamma_deg: 89.999_999_999_999_99,
            technique: "lispsm:minimax".to_owned(),
            resolution: 2048,
            partitions: 4,
            filter: "pcf:3".to_owned(),
            defined: true,
            undefined_reason: None,
            visible: 1 << 40,
            misclassified: Some(0),
            falsely_lit: Some(12),
            falsely_shadowed: Some(i64::MAX.unsigned_abs()),
            texels: Some(4 * 2048 * 2048),
            footprint_max: Some(f64::INFINITY),
            footprint_p99: Some(f64::MIN_POSITIVE / 8.0),
            footprint_mean: Some(f64::NAN),
            planning_ms: Some(0.012_5),
            shadow_pass_ms: Some(f64::MAX),
            lookup_ms: Some(-1.5),
            cell_ms: 1234.5,
        }
    }

    /// A cell whose technique is not defined: every optional field `None`.
    fn undefined(cell: u64) -> CellRecord {
        CellRecord {
            defined: false,
            undefined_reason: Some(
                "γ below φ, \"narrow\" case, λ2 < 0\nsee formulas.md".to_owned(),
            ),
            misclassified: None,
            falsely_lit: None,
            falsely_shadowed: None,
            texels: None,
            footprint_max: None,
            footprint_p99: None,
            footprint_mean: None,
            planning_ms: None,
            shadow_pass_ms: None,
            lookup_ms: None,
            ..defined(cell)
        }
    }

    /// Three records: one undefined with every option `None`, one with commas, quotes and
    /// non-ASCII text in its strings.
    fn records() -> Vec<CellRecord> {
        let mut odd = defined(1);
        odd.scene = "a, \"quoted\" scene — γ".to_owned();
        odd.technique = "cad:eq18,sin2".to_owned();
        odd.filter = "\r\n".to_owned();
        odd.undefined_reason = Some(String::new());
        vec![defined(0), odd, undefined(2)]
    }

    /// Reads a Parquet file back: its column names and its rows.
    fn read(bytes: &[u8]) -> (Vec<String>, Vec<Row>) {
        let mut file = tempfile::tempfile().expect("a temporary file");
        file.write_all(bytes).expect("written");
        let reader = SerializedFileReader::new(file).expect("a Parquet file");
        let metadata = reader.metadata();
        assert_eq!(metadata.num_row_groups(), 1);
        let names = metadata
            .file_metadata()
            .schema_descr()
            .columns()
            .iter()
            .map(|c| c.name().to_owned())
            .collect();
        let rows = reader
            .get_row_iter(None)
            .expect("rows")
            .collect::<Result<Vec<Row>, _>>()
            .expect("readable rows");
        let count = usize::try_from(metadata.file_metadata().num_rows()).expect("a row count");
        assert_eq!(rows.len(), count);
        (names, rows)
    }

    /// The field named `name` of `row`.
    fn field<'a>(row: &'a Row, name: &str) -> &'a Field {
        row.get_column_iter()
            .find(|(n, _)| *n == name)
            .map_or_else(|| panic!("no column {name}"), |(_, f)| f)
    }

    fn text(row: &Row, name: &str) -> String {
        opt_text(row, name).unwrap_or_else(|| panic!("{name} is null"))
    }

    fn opt_text(row: &Row, name: &str) -> Option<String> {
        match field(row, name) {
            Field::Null => None,
            Field::Str(s) => Some(s.clone()),
            other => panic!("{name}: {other:?} is not a string"),
        }
    }

    fn count(row: &Row, name: &str) -> u64 {
        opt_count(row, name).unwrap_or_else(|| panic!("{name} is null"))
    }

    fn opt_count(row: &Row, name: &str) -> Option<u64> {
        match field(row, name) {
            Field::Null => None,
            Field::Long(v) => Some(u64::try_from(*v).expect("not negative")),
            other => panic!("{name}: {other:?} is not an INT64"),
        }
    }

    fn index(row: &Row, name: &str) -> u32 {
        u32::try_from(count(row, name)).expect("a u32")
    }

    fn real(row: &Row, name: &str) -> f64 {
        opt_real(row, name).unwrap_or_else(|| panic!("{name} is null"))
    }

    fn opt_real(row: &Row, name: &str) -> Option<f64> {
        match field(row, name) {
            Field::Null => None,
            Field::Double(v) => Some(*v),
            other => panic!("{name}: {other:?} is not a DOUBLE"),
        }
    }

    fn flag(row: &Row, name: &str) -> bool {
        match field(row, name) {
            Field::Bool(b) => *b,
            other => panic!("{name}: {other:?} is not a BOOLEAN"),
        }
    }

    /// The record a row holds, read field by field under the record's own names.
    fn record(row: &Row) -> CellRecord {
        assert_eq!(row.len(), COLUMNS.len());
        CellRecord {
            cell: count(row, "cell"),
            scene: text(row, "scene"),
            camera: index(row, "camera"),
            light: index(row, "light"),
            light_x: real(row, "light_x"),
            light_y: real(row, "light_y"),
            light_z: real(row, "light_z"),
            gamma_deg: real(row, "gamma_deg"),
            technique: text(row, "technique"),
            resolution: index(row, "resolution"),
            partitions: index(row, "partitions"),
            filter: text(row, "filter"),
            defined: flag(row, "defined"),
            undefined_reason: opt_text(row, "undefined_reason"),
            visible: count(row, "visible"),
            misclassified: opt_count(row, "misclassified"),
            falsely_lit: opt_count(row, "falsely_lit"),
            falsely_shadowed: opt_count(row, "falsely_shadowed"),
            texels: opt_count(row, "texels"),
            footprint_max: opt_real(row, "footprint_max"),
            footprint_p99: opt_real(row, "footprint_p99"),
            footprint_mean: opt_real(row, "footprint_mean"),
            planning_ms: opt_real(row, "planning_ms"),
            shadow_pass_ms: opt_real(row, "shadow_pass_ms"),
            lookup_ms: opt_real(row, "lookup_ms"),
            cell_ms: real(row, "cell_ms"),
        }
    }

    /// Every f64 of a record, as bits.
    fn float_bits(r: &CellRecord) -> Vec<Option<u64>> {
        let required =
            [r.light_x, r.light_y, r.light_z, r.gamma_deg, r.cell_ms].map(|v| Some(v.to_bits()));
        let optional = [
            r.footprint_max,
            r.footprint_p99,
            r.footprint_mean,
            r.planning_ms,
            r.shadow_pass_ms,
            r.lookup_ms,
        ]
        .map(|v| v.map(f64::to_bits));
        required.into_iter().chain(optional).collect()
    }

    fn header() -> Vec<String> {
        let table = csv(&[]);
        let line = table.strip_suffix('\n').expect("one line");
        line.split(',').map(str::to_owned).collect()
    }

    #[test]
    fn columns_are_the_record_fields_in_order() {
        // serde writes a struct's fields in declaration order, under their names.
        let json = serde_json::to_string(&defined(0)).expect("JSON");
        let object: serde_json::Map<String, serde_json::Value> =
            serde_json::from_str(&json).expect("an object");
        assert_eq!(object.len(), COLUMNS.len());
        let positions: Vec<usize> = COLUMNS
            .iter()
            .map(|c| json.find(&format!("\"{}\":", c.name)).expect("a field"))
            .collect();
        assert!(positions.is_sorted(), "{positions:?}");
    }

    #[test]
    fn csv_header_none_and_quoting() {
        let names: Vec<&str> = COLUMNS.iter().map(|c| c.name).collect();
        assert_eq!(header(), names);
        let table = csv(&records());
        let lines: Vec<&str> = table.split_inclusive('\n').collect();
        assert_eq!(lines[0], format!("{}\n", names.join(",")));
        assert_eq!(
            lines[1],
            "0,outdoor,2,7,0.30000000000000004,-0.0,1e-300,89.99999999999999,lispsm:minimax,2048,4,\
             pcf:3,true,,1099511627776,0,12,9223372036854775807,16777216,inf,2.781342323134e-309,NaN,\
             0.0125,1.7976931348623157e308,-1.5,1234.5\n"
        );
        // Quoted fields, an empty (`Some("")`) reason, then a CRLF inside a quoted field.
        assert!(
            lines[2].starts_with(
                "1,\"a, \"\"quoted\"\" scene — γ\",2,7,0.30000000000000004,-0.0,1e-300,\
                 89.99999999999999,\"cad:eq18,sin2\",2048,4,\"\r\n"
            ),
            "{:?}",
            lines[2]
        );
        assert_eq!(
            lines[3],
            "\",true,,1099511627776,0,12,9223372036854775807,16777216,inf,\
                              2.781342323134e-309,NaN,0.0125,1.7976931348623157e308,-1.5,1234.5\n"
        );
        // Every optional field empty; the reason quoted for its comma, quotes and LF.
        assert_eq!(
            format!("{}{}", lines[4], lines[5]),
            "2,outdoor,2,7,0.30000000000000004,-0.0,1e-300,89.99999999999999,lispsm:minimax,2048,\
             4,pcf:3,false,\"γ below φ, \"\"narrow\"\" case, λ2 < 0\nsee formulas.md\",\
             1099511627776,,,,,,,,,,,1234.5\n"
        );
        assert_eq!(lines.len(), 6);
        assert_eq!(csv(&records()), table);
    }

    #[test]
    fn csv_reads_back_f64_bit_for_bit() {
        let table = csv(&[defined(0)]);
        let row = table.lines().nth(1).expect("a row");
        let fields: Vec<&str> = row.split(',').collect();
        let column = |name: &str| {
            COLUMNS
                .iter()
                .position(|c| c.name == name)
                .expect("a column")
        };
        let read = |name: &str| fields[column(name)].parse::<f64>().expect("a number");
        let r = defined(0);
        for (name, value) in [
            ("light_x", r.light_x),
            ("light_y", r.light_y),
            ("light_z", r.light_z),
            ("gamma_deg", r.gamma_deg),
            ("footprint_p99", r.footprint_p99.unwrap_or_default()),
            ("shadow_pass_ms", r.shadow_pass_ms.unwrap_or_default()),
            ("cell_ms", r.cell_ms),
        ] {
            assert_eq!(read(name).to_bits(), value.to_bits(), "{name}");
        }
    }

    #[test]
    fn parquet_round_trip() {
        let records = records();
        let (names, rows) = read(&parquet(&records).expect("written"));
        assert_eq!(names, header());
        assert_eq!(rows.len(), records.len());
        for (row, original) in rows.iter().zip(&records) {
            let back = record(row);
            // `PartialEq` compares NaN unequal and -0.0 equal to 0.0: compare the floats' bits.
            assert_eq!(float_bits(&back), float_bits(original));
            let without_floats = |r: &CellRecord| CellRecord {
                light_x: 0.0,
                light_y: 0.0,
                light_z: 0.0,
                gamma_deg: 0.0,
                footprint_max: r.footprint_max.map(|_| 0.0),
                footprint_p99: r.footprint_p99.map(|_| 0.0),
                footprint_mean: r.footprint_mean.map(|_| 0.0),
                planning_ms: r.planning_ms.map(|_| 0.0),
                shadow_pass_ms: r.shadow_pass_ms.map(|_| 0.0),
                lookup_ms: r.lookup_ms.map(|_| 0.0),
                cell_ms: 0.0,
                ..r.clone()
            };
            assert_eq!(without_floats(&back), without_floats(original));
        }
        // The undefined record reads back with nulls, not zeros.
        assert!(matches!(field(&rows[2], "texels"), Field::Null));
        assert!(matches!(field(&rows[2], "lookup_ms"), Field::Null));
        assert_eq!(opt_text(&rows[1], "undefined_reason"), Some(String::new()));
    }

    #[test]
    fn parquet_is_deterministic() {
        let records = records();
        let first = parquet(&records).expect("written");
        assert_eq!(parquet(&records).expect("written"), first);
        assert_eq!(&first[..4], b"PAR1");
        assert_eq!(&first[first.len() - 4..], b"PAR1");
    }

    #[test]
    fn parquet_of_no_records() {
        let (names, rows) = read(&parquet(&[]).expect("written"));
        assert_eq!(names, header());
        assert!(rows.is_empty());
    }

    #[test]
    fn parquet_refuses_a_count_beyond_int64() {
        let mut record = defined(0);
        record.texels = Some(u64::MAX);
        let error = parquet(&[defined(0), record]).expect_err("out of range");
        assert!(
            matches!(
                error,
                TableError::OutOfRange {
                    column: "texels",
                    row: 1,
                    value: u64::MAX
                }
            ),
            "{error:?}"
        );
        assert!(error.to_string().contains("`texels` of row 1"), "{error}");
    }
}
