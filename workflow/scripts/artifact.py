"""One artifact job (brdfs.pipeline.job.run): in the pre-loaded parent that `make all` starts
(brdfs.pipeline.zygote), else in this process."""

from brdfs.pipeline import zygote

job = dict(name=snakemake.wildcards.name, log=snakemake.log[0],  # noqa: F821 (injected by Snakemake)
           outputs=list(snakemake.output), tables=list(snakemake.input.tables),  # noqa: F821
           config=snakemake.config)  # noqa: F821 (params.config is only a digest)
if not zygote.run_in_zygote(job):
    from brdfs.pipeline import job as artifact_job

    artifact_job.run(**job)
