/*
 * outdir.h - the output folder of one invocation: never two invocations'
 * files mixed, never a folder deleted that swarmsim did not make.
 *
 * A folder swarmsim makes carries a marker file, OUTDIR_MARKER, holding one
 * line that identifies the invocation (what must be equal for --resume to
 * continue it: the effective scenario's hash, seeds, steps, outputs).
 *   new      the folder must not exist or be empty (the default);
 *   replace  a non-empty folder is removed first, only if it has the marker
 *            (`--out ~` can never erase a home);
 *   resume   the folder must have the marker with the same identity; its
 *            finished runs are kept and the others run;
 *   default  the scenario's own folder (no --out given): replaced when it
 *            has the marker, as `replace`; refused when it does not.
 * A run writes into run_<seed>.partial/ and gets its final name only when
 * it finished, so a run stopped or failed half-way leaves nothing under a
 * final name.
 */
#ifndef SIM_OUTDIR_H
#define SIM_OUTDIR_H

#include "swarmsim/base.h"

#define OUTDIR_MARKER ".swarmsim-out"

typedef enum outdir_mode { OUTDIR_NEW, OUTDIR_REPLACE, OUTDIR_RESUME, OUTDIR_DEFAULT } outdir_mode_t;

/** Makes `dir` ready for the invocation `ident` (one line, no newline).
 *  Returns 0, or -1 with a message in `err` and nothing changed. */
int outdir_prepare(const char *dir, outdir_mode_t mode, const char *ident, char err[SIM_ERR_MAX]);

/** mkdir -p */
int outdir_mkdirs(const char *path);

/** Removes `path` and everything below it, following no symbolic link.
 *  A missing path is fine.  Returns 0, or -1 (errno set). */
int outdir_remove_tree(const char *path);

#endif
