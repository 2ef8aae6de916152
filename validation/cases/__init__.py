"""The papers' setups as data: geometry, materials, loads, deviations, fitted values and FE levels (SI).

:mod:`.case` defines what a case is: a load case of :mod:`ballbench.lowmodel.bearing` (the bearing and its loads,
described once at the model layer) with a name and FE levels (:class:`ContactCase`, :class:`LinearGuideCase`,
:class:`BallScrewCase`, the mesh levels); one module per paper (:mod:`.lin2017`, :mod:`.lin2019`, :mod:`.sun2021`,
:mod:`.wang2022`) declares its cases once, with the printed value and unit beside each field.  Scenes, studies,
sweeps and ``calibrate`` read these objects; none re-declares a paper's input.  Printed results are references
(:mod:`ballbench.validation.references.published`).  docs/cases.md describes the fields.

Read at the edge: :mod:`.case_file` (a case file of one's own), :mod:`.units` (the one units parser of case files,
sweep specs and calibrate specs) and :mod:`.toml_files` (reading a spec's TOML with errors that name the file).
"""
from ballbench.validation.cases.case import (FIDELITIES, BallScrewCase, ContactCase, ContactFe, LinearGuideCase,
                                             MeshLevels, ModuleFe, ModuleLevel, PairLevel, named)

__all__ = ["FIDELITIES", "BallScrewCase", "ContactCase", "ContactFe", "LinearGuideCase", "MeshLevels", "ModuleFe",
           "ModuleLevel", "PairLevel", "named"]
