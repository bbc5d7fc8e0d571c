/*
 * outdir.c - preparing an invocation's output folder (outdir.h).
 */
#define _XOPEN_SOURCE 700   /* nftw */
#include "outdir.h"

#include <dirent.h>
#include <errno.h>
#include <ftw.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define PATH_LEN 1024

int outdir_mkdirs(const char *path)
{
    char buf[PATH_LEN];
    if (snprintf(buf, sizeof buf, "%s", path) >= (int)sizeof buf) {
        errno = ENAMETOOLONG;
        return -1;
    }
    for (char *p = buf + 1; *p; p++) {
        if (*p == '/') {
            *p = '\0';
            if (mkdir(buf, 0777) != 0 && errno != EEXIST) return -1;
            *p = '/';
        }
    }
    return (mkdir(buf, 0777) != 0 && errno != EEXIST) ? -1 : 0;
}

static int remove_entry(const char *path, const struct stat *st, int type, struct FTW *ftw)
{
    (void)st;
    (void)ftw;
    return (type == FTW_DP ? rmdir(path) : unlink(path)) != 0 ? -1 : 0;
}

int outdir_remove_tree(const char *path)
{
    struct stat st;
    if (lstat(path, &st) != 0) {
        return errno == ENOENT ? 0 : -1;
    }
    if (!S_ISDIR(st.st_mode)) {
        return unlink(path);
    }
    return nftw(path, remove_entry, 16, FTW_DEPTH | FTW_PHYS);
}

/* 1: no entries, 0: some, -1: cannot read (errno). */
static int is_empty(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return -1;
    struct dirent *e;
    int empty = 1;
    while ((e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0) {
            empty = 0;
            break;
        }
    }
    closedir(d);
    return empty;
}

/* The marker's line into buf: 1 read, 0 no marker, -1 unreadable. */
static int read_marker(const char *dir, char *buf, size_t len)
{
    char path[PATH_LEN];
    snprintf(path, sizeof path, "%s/" OUTDIR_MARKER, dir);
    FILE *f = fopen(path, "r");
    if (!f) return errno == ENOENT ? 0 : -1;
    if (!fgets(buf, (int)len, f)) buf[0] = '\0';
    fclose(f);
    buf[strcspn(buf, "\n")] = '\0';
    return 1;
}

static int write_marker(const char *dir, const char *ident)
{
    char path[PATH_LEN], tmp[PATH_LEN + 8];
    snprintf(path, sizeof path, "%s/" OUTDIR_MARKER, dir);
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    FILE *f = fopen(tmp, "w");
    if (!f) return -1;
    fprintf(f, "%s\n", ident);
    int bad = ferror(f);
    if (fclose(f) != 0 || bad || rename(tmp, path) != 0) {
        remove(tmp);
        return -1;
    }
    return 0;
}

int outdir_prepare(const char *dir, outdir_mode_t mode, const char *ident, char err[SIM_ERR_MAX])
{
    struct stat st;
    char have[SIM_ERR_MAX];
    int exists = stat(dir, &st) == 0;
    if (exists && !S_ISDIR(st.st_mode)) {
        snprintf(err, SIM_ERR_MAX, "%s: exists and is not a folder", dir);
        return -1;
    }
    int empty = exists ? is_empty(dir) : 1;
    if (empty < 0) {
        snprintf(err, SIM_ERR_MAX, "%s: cannot read: %s", dir, strerror(errno));
        return -1;
    }
    int marked = exists ? read_marker(dir, have, sizeof have) : 0;
    if (mode == OUTDIR_RESUME) {
        if (marked != 1) {
            snprintf(err, SIM_ERR_MAX, "--resume: %s is %s: nothing of swarmsim's to continue", dir,
                     !exists ? "not there" : "not a swarmsim output folder (no " OUTDIR_MARKER ")");
            return -1;
        }
        if (strcmp(have, ident) != 0) {
            snprintf(err, SIM_ERR_MAX, "--resume: %s holds another invocation's runs (scenario, seeds, "
                     "steps or outputs differ): it has [%.180s], this is [%.180s]", dir, have, ident);
            return -1;
        }
        return 0;
    }
    if (!empty) {
        if (mode == OUTDIR_NEW) {
            snprintf(err, SIM_ERR_MAX, "%s: not empty (an earlier invocation's outputs?); add --replace to "
                     "replace it (only a folder swarmsim made), --resume to continue it, or give another --out "
                     "(without --out, out/<scenario> is replaced on every run)", dir);
            return -1;
        }
        const char *how = mode == OUTDIR_DEFAULT ? "the default --out" : "--replace";
        if (marked != 1) {
            snprintf(err, SIM_ERR_MAX, "%s: %s was not made by swarmsim (no " OUTDIR_MARKER
                     "): refusing to delete it; give another --out", how, dir);
            return -1;
        }
        if (outdir_remove_tree(dir) != 0) {
            snprintf(err, SIM_ERR_MAX, "%s: cannot remove %s: %s", how, dir, strerror(errno));
            return -1;
        }
    }
    if (outdir_mkdirs(dir) != 0 || write_marker(dir, ident) != 0) {
        snprintf(err, SIM_ERR_MAX, "%s: cannot create: %s", dir, strerror(errno));
        return -1;
    }
    return 0;
}
