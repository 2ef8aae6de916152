"""Contact mechanics: exact Hertz point contact and friction over a contact ellipse."""
