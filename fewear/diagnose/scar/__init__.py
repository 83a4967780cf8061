"""The diagnosis of a measured wear scar: is the believed scar model (``fewear scar``'s case with
the source's wear coefficient) wrong, by which cause, and how much better does the fitted model
predict the profile points it was not fitted on (:mod:`fewear.diagnose.scar.diagnose`)."""
