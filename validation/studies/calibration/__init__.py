"""The one calibration home of validation (docs/calibration.md); the fits and the calibration file live in the
lowmodel layer (:mod:`ballbench.lowmodel.calibration`).

* :mod:`.spec`: the spec of ``ballbench calibrate SPEC`` checked before any work, the CSV data it names, the fits
  it runs and the calibration file written;
* :mod:`.fe_laws`: the FE load sweep of a contact case and the contact law fitted to it (a scene's case or a case
  file's contact);
* :mod:`.command`: the ``calibrate`` command and the ``--calibration FILE`` option of ``validate``
  (:func:`.command.active_calibration`, read by the scenes that take calibrated constants);
* :mod:`.roundtrip`: the synthetic round trip of the fits (the calibration scenes of scenes/calibration.py).

The calibration pictures are :func:`ballbench.validation.figures.hertz.approach_law`.
"""
