"""Module (e): the instrument. The optical head of an AFM and its laser alignment, as physics."""
