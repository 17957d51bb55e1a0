"""Research reproductions of the ball's rate-dependent impact laws (issue 33), outside the installed package."""
