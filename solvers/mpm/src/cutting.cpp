// filled in slice 4
