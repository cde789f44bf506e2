"""The cross-feature battery (issue 21): metamorphic relations over generated scenes and studies."""
