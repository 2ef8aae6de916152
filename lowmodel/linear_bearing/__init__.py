"""Linear ball bearing (lin2019 Sec 2): single ball, ball-to-ball (B2B) contact, analytical B2B model."""
