"""The method both data kinds share: nested-model statistics, the evidence for a cause and the
rule that accepts it, the report's skeleton."""
