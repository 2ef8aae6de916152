"""Linear ball bearing: rigid four-point rolling/sliding (``fourpoint``, lin2017), single ball
(``ball``, lin2019 Sec 2.1), ball-to-ball (B2B) contact (``b2b``, Sec 2.2), analytical B2B model
(``b2b_analytical``, Sec 2.3), and the B2B solve with sampled contact tractions (``b2b_traction``)."""
