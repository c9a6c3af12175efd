//! Resizable HDF5 datasets shared by SkyForge's HDF5 writers: creating
//! a dataset that grows along its first axis, appending rows to it, writing text
//! attributes and creating the groups that hold them.

use hdf5::types::{TypeDescriptor, VarLenUnicode};
use hdf5::{Dataset, Extents, Group, H5Type, Location};
use ndarray::ArrayView2;

/// Create the group `name` in `parent`, without modification times (the same run writes
/// the same bytes).
pub fn create_group(parent: &Group, name: &str) -> hdf5::Result<Group> {
    parent
        .create_group_builder()
        .obj_track_times(false)
        .create(name)
}

/// Create the per-epoch table file at `path` with its `schema` attribute and the
/// `start_gpst` its `t_s` column counts from (empty without epochs).
pub fn create_epoch_file(
    path: &std::path::Path,
    schema: &str,
    start: Option<hifitime::Epoch>,
) -> hdf5::Result<hdf5::File> {
    let file = hdf5::File::create(path)?;
    text_attr(&file, "schema", schema)?;
    text_attr(
        &file,
        "start_gpst",
        &start.map_or(String::new(), |t| t.to_string()),
    )?;
    Ok(file)
}

/// Create the file at `path` with its `schema_version` and `generator` attributes.
pub fn create_versioned_file(
    path: &std::path::Path,
    schema_version: &str,
    generator: &str,
) -> hdf5::Result<hdf5::File> {
    let file = hdf5::File::create(path)?;
    text_attr(&file, "schema_version", schema_version)?;
    text_attr(&file, "generator", generator)?;
    Ok(file)
}

/// Write the UTF-8 string attribute `name` on `loc`.
pub fn text_attr(loc: &Location, name: &str, value: &str) -> hdf5::Result<()> {
    let v: VarLenUnicode = value
        .parse()
        .map_err(|e| hdf5::Error::from(format!("{e}")))?;
    loc.new_attr::<VarLenUnicode>()
        .create(name)?
        .write_scalar(&v)
}

/// Create an empty dataset resizable along its first axis: 1-D (`width == 0`) or
/// `[row, width]`, stored in chunks of `chunk_rows` rows, with the text attributes `units`
/// and `description`. Integer masks and indices are LZF-compressed (they shrink tenfold
/// for almost nothing); floating-point values are stored raw, because compressing the
/// truth geometry cost 5 s per 24 h run for 20 % space.
pub fn create_rows<T: H5Type>(
    group: &Group,
    name: &str,
    width: usize,
    chunk_rows: usize,
    unit: &str,
    description: &str,
) -> hdf5::Result<Dataset> {
    let mut builder = group.new_dataset::<T>().obj_track_times(false);
    if matches!(
        T::type_descriptor(),
        TypeDescriptor::Integer(_) | TypeDescriptor::Unsigned(_)
    ) {
        builder = builder.lzf();
    }
    let ds = if width == 0 {
        builder
            .chunk((chunk_rows,))
            .shape(Extents::resizable(0.into()))
            .create(name)?
    } else {
        builder
            .chunk((chunk_rows, width))
            .shape(Extents::from([(0, None), (width, Some(width))].as_slice()))
            .create(name)?
    };
    text_attr(&ds, "units", unit)?;
    text_attr(&ds, "description", description)?;
    Ok(ds)
}

/// Append `data` (whole rows of `width` values, row-major; one value per row when
/// `width == 0`) to a dataset of [`create_rows`] that holds `rows` rows so far.
pub fn append_rows<T: H5Type>(
    ds: &Dataset,
    rows: usize,
    data: &[T],
    width: usize,
) -> hdf5::Result<()> {
    let n = data.len() / width.max(1);
    if width == 0 {
        ds.resize((rows + n,))?;
        ds.write_slice(data, rows..rows + n)
    } else {
        ds.resize((rows + n, width))?;
        let view = ArrayView2::from_shape((n, width), data)
            .map_err(|e| hdf5::Error::from(e.to_string()))?;
        ds.write_slice(view, (rows..rows + n, ..))
    }
}

/// The text attribute `name` of `file` (at `path`).
pub fn read_text_attr(
    file: &hdf5::File,
    path: &std::path::Path,
    name: &str,
) -> Result<String, crate::FormatError> {
    file.attr(name)
        .and_then(|a| a.read_scalar::<VarLenUnicode>())
        .map(|s| s.as_str().to_string())
        .map_err(|e| crate::FormatError::file(path, format!("attribute {name}: {e}")))
}

/// Dataset `name` of `file` (at `path`) read whole, refused beyond `max_elements` values.
pub fn read_column<T: H5Type>(
    file: &hdf5::File,
    path: &std::path::Path,
    name: &str,
    max_elements: usize,
) -> Result<Vec<T>, crate::FormatError> {
    let err = |m: String| crate::FormatError::file(path, format!("dataset {name}: {m}"));
    let ds = file.dataset(name).map_err(|e| err(e.to_string()))?;
    if ds.size() > max_elements {
        return Err(err(format!(
            "{} values; at most {max_elements} are read",
            ds.size()
        )));
    }
    ds.read_raw().map_err(|e| err(e.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn appended_rows_read_back_in_order_with_their_attributes() {
        let dir = tempfile::tempdir().unwrap();
        let file = hdf5::File::create(dir.path().join("rows.h5")).unwrap();
        let group = create_group(&file, "series").unwrap();
        let scalar = create_rows::<u16>(&group, "index", 0, 4, "1", "an index").unwrap();
        let matrix = create_rows::<f64>(&group, "r_m", 3, 4, "m", "a position").unwrap();
        append_rows(&scalar, 0, &[1u16, 2, 3], 0).unwrap();
        append_rows(&scalar, 3, &[4u16, 5, 6, 7, 8], 0).unwrap();
        append_rows(&matrix, 0, &[1.0, 2.0, 3.0], 3).unwrap();
        append_rows(&matrix, 1, &[4.0, 5.0, 6.0, 7.0, 8.0, 9.0], 3).unwrap();
        let scalar = file.dataset("series/index").unwrap();
        assert_eq!(scalar.read_raw::<u16>().unwrap(), [1, 2, 3, 4, 5, 6, 7, 8]);
        assert_eq!(matrix.shape(), [3, 3]);
        let m = matrix.read_2d::<f64>().unwrap();
        assert_eq!(m.row(2).to_vec(), [7.0, 8.0, 9.0]);
        let unit: VarLenUnicode = matrix.attr("units").unwrap().read_scalar().unwrap();
        assert_eq!(unit.as_str(), "m");
        let desc: VarLenUnicode = scalar.attr("description").unwrap().read_scalar().unwrap();
        assert_eq!(desc.as_str(), "an index");
    }
}
