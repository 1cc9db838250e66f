from pydantic import BaseModel, Field

from app.schemas.cases import CellPublic


class RowPublic(BaseModel):
    key: str
    printed: str
    plain: str
    header: bool


class ColumnPublic(BaseModel):
    id: str
    column: int
    title: str
    href: str


class GridRow(BaseModel):
    """One row of the table as laid out: merged cells appear once, with their colspan."""

    key: str
    cells: list[CellPublic]


class TablePublic(BaseModel):
    id: str
    number: int
    caption_printed: str
    caption_plain: str
    remark_printed: str
    rows: list[RowPublic]
    columns: list[ColumnPublic]
    grid: list[GridRow]
    mark_counts: dict[str, int] = Field(default_factory=dict, description="the table's "
                                        "cells (one per body and row) per mark")
    summary: str = Field("", description="mark_counts in words")
