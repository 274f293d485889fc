// Tests for curves/: being written.
