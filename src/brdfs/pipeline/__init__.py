"""Pipeline plumbing: configuration, the artifact registry, I/O, published values, regression, plotting."""
