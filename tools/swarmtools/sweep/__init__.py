"""One sweep engine for every study: a sweep file expanded into runs with
stable ids, run here (all cores) or on a SLURM cluster (job arrays),
resumable, into one tidy table (CSV and Parquet). See cli.py and spec.py."""
