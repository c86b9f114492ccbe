"""What a run leaves: the contact records (:mod:`~flexbeam.results.records`), the arrays evaluated on demand from
the dense output (:mod:`~flexbeam.results.arrays`), the force peaks (:mod:`~flexbeam.results.peaks`), what one
contact is (:mod:`~flexbeam.results.counts`), the metrics (:mod:`~flexbeam.results.metrics` names them,
:mod:`~flexbeam.results.summary` computes them), the :class:`~flexbeam.results.solution.Solution` and its
export to xarray and NetCDF (:mod:`~flexbeam.results.export`, :mod:`~flexbeam.results.files`).
"""
