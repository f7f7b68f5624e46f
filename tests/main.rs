mod boundaries;
