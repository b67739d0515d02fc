"""Evaluation harnesses on top of generation (the generation benchmark).

Submodules are imported explicitly (``from factask.evaluation.benchmark import
run_benchmark``) so importing this package stays cheap.
"""
