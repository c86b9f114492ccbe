"""What a user looks at: figures (:mod:`~flexbeam.views.plotting`), the notebook display
(:mod:`~flexbeam.views.display`), animations (:mod:`~flexbeam.views.animation`), the files of a run
(:mod:`~flexbeam.views.report`) and the accessor that links a Solution to them (:mod:`~flexbeam.views.accessor`).

The views read results and never feed back: nothing below this package imports it.
"""
