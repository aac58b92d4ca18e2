"""`make study`: the studies of the sampler, estimator, light-selection, adaptive-sampling,
radiosity and path-guiding issues, their pages and figures in out/study/. run.py plans the
`stratum compare` runs and holds the command line; each part (estimators.py, lights.py,
adaptive.py, radiosity.py, guiding.py with guiding_page.py, auto_lights.py) writes its page;
summary.py and figures.py gather them. results.py reads a run's results.json, plotting.py is
what every figure is drawn with."""
