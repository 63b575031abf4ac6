/* No network where the docs are built or read: math stays as its TeX source (conf.py, mathjax_path). */
