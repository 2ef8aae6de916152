"""Published inputs and printed numbers of the source papers, declared once as data.

One small module per paper (``lin2019``, ``lin2017``, ``wang2022``; ``sun2021``
later).  Each holds frozen dataclasses whose fields are in SI units; the
paper's printed value and unit sit in the comment beside the field, and the
conversion happens here, at this edge, nowhere else.  Scenes read these
objects; they never re-declare a paper's number.
"""
