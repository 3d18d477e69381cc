/* rockdem (private) — plain HDF5 tables in the output's layout-2 style (docs/HDF5-LAYOUT.md):
 * 1-D or 2-D datasets of doubles, ints or bytes with `units` and `long_name`, every axis
 * attached to an HDF5 dimension scale, and variable-length UTF-8 string lists. Intermediate
 * groups are created on the way. Used for /history, /joints and /outcomes in a run's output
 * and for checkpoints (`model save`). Locations are HDF5 ids (hid_t) passed as long long, so
 * callers need not include hdf5.h.
 * Folder io/ owns the HDF5 output file; it may call base/ and the public headers, never engine/
 * internals or cli/.
 */
#ifndef RD_IO_TABLE_H
#define RD_IO_TABLE_H

#include "rockdem/error.h"

typedef enum rd_h5t_type {
    RD_H5T_DOUBLE = 0,
    RD_H5T_INT = 1,
    RD_H5T_BYTE = 2,
    RD_H5T_LONG = 3
} rd_h5t_type;

/* The axes of a table: each names a dimension scale (a path from loc, or absolute). A scale
 * that does not exist yet is created: from `labels` (comma-separated strings, one per row of
 * that axis) when given, else as the indices 0..n-1. NULL dim: the axis gets no scale (only
 * for checkpoints, which are not meant to be browsed). */
typedef struct rd_h5t_axes {
    const char *dim[2];
    const char *labels[2];
} rd_h5t_axes;

/* Create (truncate) or open (read-only) a file: its id, or -1 with err set. */
long long rd_h5t_create(const char *path, rd_error *err);
long long rd_h5t_open(const char *path, rd_error *err);
void rd_h5t_close(long long file);

/* Write dataset `name` under loc: rows x cols (cols 0: 1-D of rows) of type t, with units
 * (may be NULL) and long_name (NULL: none) attributes and the axes' scales. 0 or -1. */
int rd_h5t_write(long long loc, const char *name, rd_h5t_type t, const void *data, long rows,
                 int cols, const char *units, const char *long_name, const rd_h5t_axes *axes,
                 rd_error *err);
/* Overwrite rows [first, first + rows) of the existing dataset `name` (1-D, or 2-D of its
 * own width) with data of type t. 0 or -1. */
int rd_h5t_write_rows(long long loc, const char *name, rd_h5t_type t, const void *data, long first,
                      long rows, rd_error *err);
/* A variable-length UTF-8 string attribute `key` = value on the object `name` under loc
 * (created, or replaced). 0 or -1. */
int rd_h5t_attr(long long loc, const char *name, const char *key, const char *value, rd_error *err);
/* Open (creating it when missing) group `name` under loc: its id, or -1. */
long long rd_h5t_group(long long loc, const char *name, rd_error *err);
void rd_h5t_close_group(long long g);
/* Make the existing 1-D dataset `name` a dimension scale. 0 or -1. */
int rd_h5t_make_scale(long long loc, const char *name, rd_error *err);
/* Hard-link into every group under `name` (recursively) each dimension scale that one of its
 * datasets uses and that lives elsewhere, under the scale's own name: netCDF readers (xarray's
 * h5netcdf engine) take a group's coordinates only from its own members, so /ground opens
 * with `time` and `xyz`, /history/body/NAME with `time`. The data is shared, not copied. A
 * name already taken in the group is left alone. 0 or -1. */
int rd_h5t_link_scales(long long loc, const char *name, rd_error *err);
/* Read dataset `name` of exactly n elements of type t into data. 0 or -1 (missing, wrong size). */
int rd_h5t_read(long long loc, const char *name, rd_h5t_type t, void *data, long n, rd_error *err);
/* Number of elements of dataset `name`, -1 when missing. */
long rd_h5t_count(long long loc, const char *name);
/* Write a 1-D dataset of n variable-length UTF-8 strings (axis: dim, may be NULL; the
 * dataset itself becomes that scale when dim equals name). 0 or -1. */
int rd_h5t_strings(long long loc, const char *name, const char *const *s, int n,
                   const char *long_name, const char *dim, rd_error *err);
/* Read string k of such a dataset into buf (size bytes). 0 or -1. */
int rd_h5t_string(long long loc, const char *name, int k, char *buf, int size, rd_error *err);

#endif
