"""The papers' printed results, declared once (SI): the numbers the scenes reproduce.

One module per paper.  The inputs that produced these numbers are cases (:mod:`ballbench.validation.cases`);
a printed value here is a reference a check compares with, with its printed form and unit in the comment.
"""
