"""Every drawing of the validation: functions that take plain arrays or results and return a
:class:`matplotlib.figure.Figure` (matplotlib's object API: no pyplot state, no backend switch; a Figure draws
with the Agg canvas when saved), and the pyvista off-screen 3D screenshots of saved fields.  Scenes save them
with ``Run.save_figure``, ``show`` hooks with :func:`.style.save`.  One module per family of pictures:
:mod:`.fe_contact` (FE contact fields), :mod:`.fe_module` (pressure patches and stress cuts of the FE modules),
:mod:`.hertz` (with the calibrated contact law beside Hertz's), :mod:`.lin2017`, :mod:`.lin2019`,
:mod:`.sun2021`, :mod:`.wang2022`;
:mod:`.render3d` (with :mod:`.views3d`, :mod:`.surfaces3d`) for the 3D screenshots (docs/render3d.md).
"""
